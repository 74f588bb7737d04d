#include "rviz_projector/core/projector_mount.h"

#include <array>
#include <cmath>

namespace rviz_projector
{
namespace
{
struct Quaternion
{
  double x, y, z, w;
};

Quaternion multiply(const Quaternion& a, const Quaternion& b)
{
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}

/// Fixed-axis roll, pitch, yaw as tf2's Quaternion::setRPY: Rz(yaw) * Ry(pitch) * Rx(roll).
Quaternion fromRpy(double roll, double pitch, double yaw)
{
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2);
  const double cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  return {sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy,
          cr * cp * cy + sr * sp * sy};
}

/// Body -> optical frame, as launch/projector.launch publishes it.
constexpr Quaternion kBodyToOptical{-0.5, 0.5, -0.5, 0.5};

/// Angle in (-pi, pi].
double wrap(double a)
{
  return a <= -M_PI ? a + 2 * M_PI : a;
}
}  // namespace

RigidTransform opticalPoseOfMount(const ProjectorMount& mount)
{
  const Quaternion q = multiply(fromRpy(mount.roll, mount.pitch, mount.yaw), kBodyToOptical);
  return RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, {mount.x, mount.y, mount.z});
}

ProjectorMount mountOfOpticalPose(const RigidTransform& parent_T_optical)
{
  const std::array<double, 9>& r = parent_T_optical.rotation();
  // Body axes in the parent frame: body x = optical z, body y = -optical x, body z = -optical y.
  // m is the body's rotation, row-major: m[3 i + j] = component i of body axis j.
  const std::array<double, 9> m = {r[2], -r[0], -r[1], r[5], -r[3], -r[4], r[8], -r[6], -r[7]};
  ProjectorMount mount;
  mount.x = parent_T_optical.translation().x;
  mount.y = parent_T_optical.translation().y;
  mount.z = parent_T_optical.translation().z;
  // m = Rz(yaw) Ry(pitch) Rx(roll): m20 = -sin(pitch), m21 = sin(roll) cos(pitch), m22 = cos(roll)
  // cos(pitch), m10 = sin(yaw) cos(pitch), m00 = cos(yaw) cos(pitch).
  const double cos_pitch = std::hypot(m[0], m[3]);
  mount.pitch = std::atan2(-m[6], cos_pitch);
  if (cos_pitch > 1e-12)
  {
    mount.roll = wrap(std::atan2(m[7], m[8]));
    mount.yaw = wrap(std::atan2(m[3], m[0]));
  }
  else
  {
    // Gimbal lock (beam straight down or up): only yaw -/+ roll is defined; all of it goes to yaw.
    // With roll = 0: m01 = -sin(yaw), m11 = cos(yaw).
    mount.roll = 0.0;
    mount.yaw = wrap(std::atan2(-m[1], m[4]));
  }
  return mount;
}
}  // namespace rviz_projector
