// Speed-coded spacing of ProjectedPath's arrows (issue 25, part 2, Stop zone > Speed-coded
// spacing): the spacing follows the speed the robot is expected to have there, so arrows crowd
// where it slows down for its destination. Plain arithmetic (no ROS, no OGRE).
#pragma once

namespace rviz_projector
{
struct SpeedCoding
{
  bool enabled = false;
  /// The robot's speed now (the Stop zone's filtered odometry speed), m/s; NaN, Inf or negative: 0.
  double speed = 0.0;
  /// The braking the robot plans with (the Stop zone's Deceleration), m/s^2; <= 0 or NaN: 0.5.
  double deceleration = 0.5;
  /// Arrow spacing = planned speed x time_step (each arrow is where the robot will be time_step later), s.
  double time_step = 0.5;
  /// The closest two arrow tips come, metres (never below path_style::kMinSpacing).
  double min_spacing = 0.1;
};

/**
 * Planned speed at `from_end` metres of path before the destination: the robot keeps its current
 * speed and brakes with `deceleration` to stop at the destination, v = min(speed, sqrt(2 a
 * from_end)). The arrow spacing there is max(min_spacing, v * time_step). Measured from the
 * destination (as Exact mode's arrows are), so the arrows stand still on the floor while the robot
 * drives at a steady speed; they only move when its speed changes. Values are sanitised as the
 * fields say; the result is always finite and >= path_style::kMinSpacing.
 */
double speedCodedSpacing(const SpeedCoding& coding, double from_end);

/// The planned speed alone (m/s), sanitised as above; from_end <= 0 or NaN: 0.
double plannedSpeed(const SpeedCoding& coding, double from_end);
}  // namespace rviz_projector
