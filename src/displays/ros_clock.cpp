#include "rviz_projector/displays/ros_clock.h"

#include <chrono>

#include <ros/time.h>

namespace rviz_projector
{
RosClock& RosClock::shared()
{
  static RosClock clock;
  return clock;
}

double RosClock::steadyNow()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

const ClockPolicy& RosClock::tick()
{
  policy_.update(ros::Time::now().toSec(), steadyNow());
  return policy_;
}
}  // namespace rviz_projector
