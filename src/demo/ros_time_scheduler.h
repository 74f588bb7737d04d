// RosTimeScheduler: periodic tasks on ROS time (simulated under /use_sim_time) without roscpp's
// ros::Timer.
//
// roscpp's TimerManager (Debian's ros_comm) handles a backward jump of ROS time only when its
// thread sees the jump at the right moment: a jump that lands while a timer's callback is queued
// or running can leave the timer waiting for its pre-jump expiry, i.e. a whole bag loop (the demo
// stood still after "new goal 1" in the sanitized CI run, and again in a normal CI run with a
// watchdog that restarted the timers). So the demo's nodes pace themselves: one steady (wall) timer
// ticks kTickRate times a second, reads ROS time, and runs each task whose next due time has come.
// A task runs at most once per tick (no burst after a pause or a forward jump); after a backward
// jump every task is due at once and counts its period from there. Under a clock faster than
// real time a task runs at most kTickRate times per wall second (documented in the demo's guide).
// Header-only; call everything from the node's thread (tasks run on the global callback queue).
#pragma once

#include <ros/ros.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace rviz_projector_demo
{
class RosTimeScheduler
{
public:
  static constexpr double kTickRate = 250.0;  // wall ticks per second

  explicit RosTimeScheduler(std::string node) : node_(std::move(node)) {}
  RosTimeScheduler(const RosTimeScheduler&) = delete;
  RosTimeScheduler& operator=(const RosTimeScheduler&) = delete;

  /// A task every `period` s of ROS time; the first run is at the first tick with a valid time.
  void add(double period, std::function<void()> task) { tasks_.push_back(Task{period, ros::Time(), std::move(task)}); }
  /// Starts ticking (on `nh`'s callback queue).
  void start(ros::NodeHandle& nh)
  {
    tick_timer_ = nh.createSteadyTimer(ros::WallDuration(1.0 / kTickRate), &RosTimeScheduler::tick, this);
  }
  /// Backward jumps seen so far.
  int jumps() const { return jumps_; }

private:
  struct Task
  {
    double period;
    ros::Time due;  // zero: at the next tick
    std::function<void()> run;
  };

  void tick(const ros::SteadyTimerEvent&)
  {
    const ros::Time now = ros::Time::now();
    if (now.isZero())
    {
      return;  // simulated time, no /clock yet
    }
    if (!last_.isZero() && now < last_)
    {
      ++jumps_;
      ROS_INFO("%s: ROS time jumped back by %.3f s: every task is due now", node_.c_str(), (last_ - now).toSec());
      for (Task& task : tasks_)
      {
        task.due = ros::Time();
      }
    }
    last_ = now;
    for (Task& task : tasks_)
    {
      if (!task.due.isZero() && now < task.due)
      {
        continue;
      }
      const ros::Duration period(task.period);
      // The next due time keeps the task's cadence; a task that fell behind starts again from now.
      task.due = task.due.isZero() || task.due + period <= now ? now + period : task.due + period;
      task.run();
    }
  }

  std::string node_;
  std::vector<Task> tasks_;
  ros::SteadyTimer tick_timer_;
  ros::Time last_;
  int jumps_ = 0;
};
}  // namespace rviz_projector_demo
