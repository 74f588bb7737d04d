// RosTimerRestarter: restarts a node's ros::Timers after ROS time jumped backwards.
//
// roscpp's TimerManager (Debian's ros_comm) resets its timers after a backward jump of ROS time
// only when its thread happens to see the jump between two of its own reads of the clock; a jump
// that lands while a timer's callback is queued or running, or between those reads, leaves the
// timer waiting for its pre-jump expiry time. Under `rosbag play --clock -l` or a simulator reset
// that is the whole jump (a loop of the bag) of ROS time: the demo stood still after "new goal 1"
// (found by test/nodes/demo_navigation_clock.test under the sanitizers, where callbacks are slow).
//
// This watchdog runs on steady (wall) time, which does not jump: every kPeriod it reads ROS time,
// and when that is earlier than at its previous check it stops and starts every timer it watches
// (a started timer's first expiry is one period after the current ROS time). A restart when
// roscpp did reset the timer itself costs one period's delay at most. Header-only; the demo nodes
// own one each. Call it from the node's thread (the global callback queue): the timers' callbacks
// run on that queue too, so none of them runs while it restarts them.
#pragma once

#include <ros/ros.h>

#include <string>
#include <utility>
#include <vector>

namespace rviz_projector_demo
{
class RosTimerRestarter
{
public:
  static constexpr double kPeriod = 0.05;  // s of wall time between two looks at ROS time

  RosTimerRestarter(ros::NodeHandle& nh, std::vector<ros::Timer*> timers, std::string node)
    : timers_(std::move(timers)), node_(std::move(node))
  {
    watchdog_ = nh.createSteadyTimer(ros::WallDuration(kPeriod), &RosTimerRestarter::check, this);
  }

  RosTimerRestarter(const RosTimerRestarter&) = delete;
  RosTimerRestarter& operator=(const RosTimerRestarter&) = delete;

  /// Restarts so far (for the log and the tests).
  int restarts() const { return restarts_; }

private:
  void check(const ros::SteadyTimerEvent&)
  {
    const ros::Time now = ros::Time::now();
    if (!now.isZero() && !last_.isZero() && now < last_)
    {
      for (ros::Timer* timer : timers_)
      {
        timer->stop();
        timer->start();
      }
      ++restarts_;
      ROS_INFO("%s: ROS time jumped back by %.3f s: its timers restarted from %.3f s", node_.c_str(),
               (last_ - now).toSec(), now.toSec());
    }
    last_ = now;
  }

  std::vector<ros::Timer*> timers_;
  std::string node_;
  ros::SteadyTimer watchdog_;
  ros::Time last_;
  int restarts_{0};
};
}  // namespace rviz_projector_demo
