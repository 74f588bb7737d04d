// One part for "a private ros::CallbackQueue drained on the GUI thread, paused while disabled"
// (issue 23), used by every subscription of this package's displays that must be prompt:
//   - ProjectedPath and ProjectionMask: a base class listed before rviz's MessageFilterDisplay, so
//     that the queue outlives the subscriber and tf filter that hold it (the filter's destructor
//     still removes its callbacks from the queue); drained by the part's own timer every
//     kDrainIntervalMs while the display is enabled (resumeDraining / pauseDraining);
//   - the ProjectorCamera's lens source and Odometry (ProjectorMotion): drained by the projector's
//     frame clock (itself stopped while the display is disabled) through drain().
// Nobody spins rviz's global queue from inside a display: rviz owns it, and one of its callbacks
// (load_config) may delete the display mid-call.
#pragma once

#include <functional>
#include <utility>

#include <QTimer>
#include <ros/callback_queue.h>
#include <ros/node_handle.h>

namespace rviz_projector
{
class PrivateCallbackQueue
{
public:
  /// How often the timer drains the queue, milliseconds.
  static constexpr int kDrainIntervalMs = 5;

  PrivateCallbackQueue() { timer_.setInterval(kDrainIntervalMs); }
  PrivateCallbackQueue(const PrivateCallbackQueue&) = delete;
  PrivateCallbackQueue& operator=(const PrivateCallbackQueue&) = delete;

  /// Subscriptions made through `nh` are handled on this queue.
  void attach(ros::NodeHandle& nh) { nh.setCallbackQueue(&queue_); }
  /// What the timer calls on the GUI thread (it drains the queue with drain(), and may do more).
  void setDrainHandler(std::function<void()> handler)
  {
    QObject::disconnect(connection_);
    connection_ = QObject::connect(&timer_, &QTimer::timeout, std::move(handler));
  }
  /// The display was enabled: drain every kDrainIntervalMs.
  void resumeDraining() { timer_.start(); }
  /// The display was disabled (or is going): nothing is drained until resumeDraining().
  void pauseDraining() { timer_.stop(); }
  bool draining() const { return timer_.isActive(); }
  /// Handles the messages waiting, on the calling thread.
  void drain() { queue_.callAvailable(); }

private:
  ros::CallbackQueue queue_;
  QTimer timer_;
  QMetaObject::Connection connection_;
};
}  // namespace rviz_projector
