#include "host_reload_service.h"

#include <chrono>
#include <future>

#include "host_session.h"

namespace rviz_projector
{
namespace
{
/// Longest a reply waits for the Qt thread (a reload loads plugins and meshes: seconds at most).
constexpr auto kReplyTimeout = std::chrono::seconds(60);
}  // namespace

HostReloadService::HostReloadService(std::function<HostLoadResult()> reload)
  : guard_(std::make_unique<QObject>()), reload_(std::move(reload)), nh_("~")
{
  nh_.setCallbackQueue(&queue_);
  server_ = nh_.advertiseService("reload", &HostReloadService::onRequest, this);
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

HostReloadService::~HostReloadService()
{
  // The guard goes first: a request waiting for the Qt thread (this one, now in here) gets a
  // broken promise at once and replies "shutting down". Shutting the server down first would drop
  // the caller's connection instead: a failed call with no reason (test/host/
  // host_reload_service_test.cpp, which also found the spinner's part below).
  {
    std::lock_guard<std::mutex> lock(guard_mutex_);
    guard_.reset();
  }
  // Then the spinner's thread is joined: the request it is answering finishes, and roscpp writes
  // its reply in that same thread right after onRequest returns. Shutting the server down while it
  // is between the two drops the connection under the reply (seen in CI: the caller's call failed).
  spinner_->stop();
  // Requests that arrived meanwhile are answered here ("shutting down"), not dropped.
  queue_.callAvailable();
  server_.shutdown();
}

bool HostReloadService::onRequest(std_srvs::Trigger::Request& /*request*/, std_srvs::Trigger::Response& response)
{
  auto promise = std::make_shared<std::promise<HostLoadResult>>();
  std::future<HostLoadResult> result = promise->get_future();
  // Queued on the Qt thread; if guard_ is destroyed first, Qt drops the call and the promise with
  // it (broken promise: the reply says so).
  bool posted = false;
  {
    std::lock_guard<std::mutex> lock(guard_mutex_);
    posted = guard_ && QMetaObject::invokeMethod(
                           guard_.get(), [promise, this] { promise->set_value(reload_()); }, Qt::QueuedConnection);
  }
  promise.reset();
  if (!posted || result.wait_for(kReplyTimeout) != std::future_status::ready)
  {
    response.success = false;
    response.message = "projector_host did not handle the reload (shutting down or busy)";
    return true;
  }
  try
  {
    const HostLoadResult done = result.get();
    response.success = done.ok;
    response.message = done.message;
  }
  catch (const std::future_error&)
  {
    response.success = false;
    response.message = "projector_host is shutting down";
  }
  return true;
}
}  // namespace rviz_projector
