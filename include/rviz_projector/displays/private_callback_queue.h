// A display's own ros::CallbackQueue, as a base class listed before rviz's MessageFilterDisplay,
// so the queue outlives the subscriber and tf filter that hold it (the filter's destructor still
// removes its callbacks from the queue). The display drains it from a timer of its own: its
// messages are handled promptly, and nobody spins rviz's global queue from inside a display.
#pragma once

#include <ros/callback_queue.h>

namespace rviz_projector
{
struct PrivateCallbackQueue
{
  ros::CallbackQueue path_queue_;
};
}  // namespace rviz_projector
