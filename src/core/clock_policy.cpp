#include "rviz_projector/core/clock_policy.h"

#include <cmath>

namespace rviz_projector
{
bool ClockPolicy::update(double ros_now, double steady_now)
{
  if (!std::isfinite(ros_now) || !std::isfinite(steady_now))
  {
    return false;  // an unusable reading changes nothing
  }
  if (!started_)
  {
    started_ = true;
    ros_now_ = anchor_ros_ = ros_now;
    steady_now_ = anchor_steady_ = steady_now;
    return false;
  }
  const bool jumped_back = ros_now < ros_now_ - kBackwardTolerance;
  if (ros_now_ == 0.0 && ros_now != 0.0)
  {
    time_started_ = true;  // a simulated clock's first tick
    start_steady_ = steady_now;
  }
  ros_now_ = ros_now;
  steady_now_ = steady_now;
  if (jumped_back)
  {
    ++epoch_;
    jump_steady_ = steady_now;
    // The rate of the clock is the same after the loop: keep it, measure afresh from here.
    anchor_ros_ = ros_now;
    anchor_steady_ = steady_now;
    return true;
  }
  const double steady_span = steady_now - anchor_steady_;
  if (steady_span >= kRateWindow)
  {
    const double measured = (ros_now - anchor_ros_) / steady_span;
    if (measured >= 0.0 && measured <= kMaxRate)
    {
      rate_ = measured;
    }
    anchor_ros_ = ros_now;
    anchor_steady_ = steady_now;
  }
  else if (steady_span < 0.0)
  {
    anchor_ros_ = ros_now;  // a steady clock never goes back; if one did, start the window again
    anchor_steady_ = steady_now;
  }
  return false;
}
}  // namespace rviz_projector
