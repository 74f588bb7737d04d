// projector_host's ~reload service (src/host/host_reload_service.cpp), with a real ROS service call
// from another thread, as `rosservice call /projector_host/reload` makes it.
//
// The order at shutdown (issue 23, defect 5): the service releases its guard (the Qt-thread
// receiver a request waits on) before it shuts its server down. The other way round the server's
// shutdown waits for the request in flight, which waits for the Qt thread, which is the one
// shutting down: projector_host would hang for the reply timeout (60 s) at every exit with a
// reload pending.
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <string>
#include <thread>

#include <QAbstractEventDispatcher>
#include <QCoreApplication>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "../../src/host/host_reload_service.h"
#include "../../src/host/host_session.h"

namespace
{
using rviz_projector::HostLoadResult;
using rviz_projector::HostReloadService;
using Clock = std::chrono::steady_clock;

/// Polls `condition` (delivering this thread's posted Qt events when `serve` is set) until it
/// holds or `seconds` pass.
template <class Condition>
bool waitFor(Condition condition, double seconds, bool serve)
{
  const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
  while (!condition())
  {
    if (Clock::now() > deadline)
    {
      return false;
    }
    if (serve)
    {
      QCoreApplication::processEvents();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}

/// `rosservice call <name>` from a thread of its own: the reply, once it came.
std::future<std_srvs::Trigger::Response> callLater(const std::string& name)
{
  return std::async(std::launch::async, [name] {
    std_srvs::Trigger srv;
    if (!ros::service::call(name, srv))
    {
      srv.response.success = false;
      srv.response.message = "<the call itself failed>";
    }
    return srv.response;
  });
}

bool ready(const std::future<std_srvs::Trigger::Response>& reply)
{
  return reply.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}
}  // namespace

TEST(HostReloadService, ReloadsOnTheQtThreadAndRepliesItsResult)
{
  std::atomic<int> reloads{0};
  std::thread::id reloaded_on;
  HostReloadService service([&] {
    reloaded_on = std::this_thread::get_id();
    ++reloads;
    return HostLoadResult{true, "loaded test.rviz", {}};
  });
  const std::string name = ros::this_node::getName() + "/reload";
  ASSERT_TRUE(ros::service::waitForService(name, ros::Duration(10.0)));
  auto reply = callLater(name);
  ASSERT_TRUE(waitFor([&] { return ready(reply); }, 20.0, true));
  const std_srvs::Trigger::Response response = reply.get();
  EXPECT_TRUE(response.success);
  EXPECT_EQ(response.message, "loaded test.rviz");
  EXPECT_EQ(reloads, 1);
  EXPECT_EQ(reloaded_on, std::this_thread::get_id()) << "the reload ran on the Qt thread";
}

TEST(HostReloadService, ShuttingDownWithARequestWaitingRepliesAtOnceAndDoesNotReload)
{
  std::atomic<int> reloads{0};
  auto service = std::make_unique<HostReloadService>([&] {
    ++reloads;
    return HostLoadResult{true, "loaded", {}};
  });
  const std::string name = ros::this_node::getName() + "/reload";
  ASSERT_TRUE(ros::service::waitForService(name, ros::Duration(10.0)));
  QAbstractEventDispatcher* dispatcher = QAbstractEventDispatcher::instance();
  ASSERT_NE(dispatcher, nullptr);
  QCoreApplication::processEvents();
  ASSERT_TRUE(waitFor([&] { return !dispatcher->hasPendingEvents(); }, 10.0, true))
      << "nothing else may be posted: the next posted event is the request";
  auto reply = callLater(name);
  // The request has reached the service and waits for this (Qt) thread, which does not serve it:
  ASSERT_TRUE(waitFor([&] { return dispatcher->hasPendingEvents(); }, 20.0, false))
      << "the request was never handed to the Qt thread";
  EXPECT_FALSE(ready(reply));
  const auto begin = Clock::now();
  service.reset();  // projector_host exiting
  const double shutdown_seconds = std::chrono::duration<double>(Clock::now() - begin).count();
  // The reply came as the guard went (the reply timeout is 60 s: 10 s is a loaded machine's margin).
  ASSERT_TRUE(waitFor([&] { return ready(reply); }, 10.0, false));
  const std_srvs::Trigger::Response response = reply.get();
  EXPECT_FALSE(response.success);
  EXPECT_NE(response.message.find("shutting down"), std::string::npos) << response.message;
  EXPECT_LT(shutdown_seconds, 10.0) << "the service's shutdown waited for the request it was to release";
  QCoreApplication::processEvents();  // a dropped call must not run later either
  EXPECT_EQ(reloads, 0);
}
