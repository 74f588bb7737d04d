// Test helper: the orientation of a projector's optical frame (z forward, x right, y down: the
// camera convention of REP-103) when the projector's body (x forward, y left, z up) is turned by
// roll, pitch and yaw. Positive pitch tilts the projector down towards the floor.
#pragma once

#include <cmath>

namespace rviz_projector_test
{
struct Quaternion
{
  double x, y, z, w;
};

/// Hamilton product a * b.
inline Quaternion operator*(const Quaternion& a, const Quaternion& b)
{
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

/// Body rotation from fixed-axis roll (x), pitch (y), yaw (z), as tf2::Quaternion::setRPY.
inline Quaternion fromRollPitchYaw(double roll, double pitch, double yaw)
{
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
          cr * cp * cy + sr * sp * sy};
}

/// Optical frame of a projector body turned by roll, pitch, yaw.
inline Quaternion opticalOrientation(double roll, double pitch, double yaw)
{
  const Quaternion body_to_optical{-0.5, 0.5, -0.5, 0.5};
  return fromRollPitchYaw(roll, pitch, yaw) * body_to_optical;
}
}  // namespace rviz_projector_test
