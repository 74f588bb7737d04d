// The process's one ClockPolicy (core/clock_policy.h) fed from ROS: ros::Time::now() and the steady
// clock. Every display of this package reads the time through it (tick() each frame or message),
// so all of them agree on the rate of ROS time and on when it jumped backwards. Tests give it a
// fixed rate when they step a simulated clock by hand. GUI thread only.
#pragma once

#include "rviz_projector/core/clock_policy.h"

namespace rviz_projector
{
/// How a status starts when tf is missing just after a backward jump (ClockPolicy::justStartedOrJumpedBack).
constexpr const char* kWaitingForTfAfterJump = "Waiting for tf after ROS time started or jumped back (a bag starting or looping?): ";

class RosClock
{
public:
  /// The instance the displays share.
  static RosClock& shared();
  /// Reads ROS now and steady now into the policy; returns it.
  const ClockPolicy& tick();
  const ClockPolicy& policy() const { return policy_; }
  ClockPolicy& policy() { return policy_; }
  /// Steady (monotonic wall) time now, seconds.
  static double steadyNow();

private:
  ClockPolicy policy_;
};
}  // namespace rviz_projector
