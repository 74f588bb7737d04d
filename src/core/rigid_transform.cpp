#include "rviz_projector/core/rigid_transform.h"

#include <cmath>

namespace rviz_projector
{
RigidTransform RigidTransform::fromQuaternion(double qx, double qy, double qz, double qw, const Vec3& translation)
{
  RigidTransform t;
  t.t_ = translation;
  const double n = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
  if (!(n > 0.0) || !std::isfinite(n))
  {
    return t;  // identity rotation for a zero or non-finite quaternion
  }
  const double x = qx / n, y = qy / n, z = qz / n, w = qw / n;
  t.r_ = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
          2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
          2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
  return t;
}

Vec3 RigidTransform::rotate(const Vec3& d) const
{
  return {r_[0] * d.x + r_[1] * d.y + r_[2] * d.z, r_[3] * d.x + r_[4] * d.y + r_[5] * d.z,
          r_[6] * d.x + r_[7] * d.y + r_[8] * d.z};
}

Vec3 RigidTransform::apply(const Vec3& p) const
{
  return rotate(p) + t_;
}
}  // namespace rviz_projector
