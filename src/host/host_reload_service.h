// projector_host's ~reload service (std_srvs/Trigger). The request arrives on a callback queue of
// its own (served by one thread of its own), is handed to the Qt thread as a queued call, and the
// reply waits for its result: the reload never runs inside rviz's update or a display's code.
#pragma once

#ifndef Q_MOC_RUN
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <QObject>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#endif

namespace rviz_projector
{
struct HostLoadResult;

class HostReloadService
{
public:
  /// Advertises ~reload; `reload` runs on the thread that constructs this object (the Qt thread).
  explicit HostReloadService(std::function<HostLoadResult()> reload);
  ~HostReloadService();

private:
  bool onRequest(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);

  /// Receiver of the queued calls, on the Qt thread; deleting it drops a call not yet run.
  std::unique_ptr<QObject> guard_;
  std::mutex guard_mutex_;  ///< guard_ is reset on the Qt thread while a request may post to it
  std::function<HostLoadResult()> reload_;
  ros::CallbackQueue queue_;
  ros::NodeHandle nh_;
  ros::ServiceServer server_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};
}  // namespace rviz_projector
