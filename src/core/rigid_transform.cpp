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

RigidTransform RigidTransform::operator*(const RigidTransform& b_T_c) const
{
  RigidTransform a_T_c;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a_T_c.r_[3 * i + j] = r_[3 * i] * b_T_c.r_[j] + r_[3 * i + 1] * b_T_c.r_[3 + j] + r_[3 * i + 2] * b_T_c.r_[6 + j];
    }
  }
  a_T_c.t_ = apply(b_T_c.t_);
  return a_T_c;
}

RigidTransform RigidTransform::inverse() const
{
  RigidTransform b_T_a;
  b_T_a.r_ = {r_[0], r_[3], r_[6], r_[1], r_[4], r_[7], r_[2], r_[5], r_[8]};
  b_T_a.t_ = b_T_a.rotate(t_) * -1.0;
  return b_T_a;
}
}  // namespace rviz_projector

namespace rviz_projector
{
RigidTransform RigidTransform::fromMatrix(const std::array<double, 9>& rotation, const Vec3& translation)
{
  RigidTransform t;
  t.r_ = rotation;
  t.t_ = translation;
  return t;
}

std::array<double, 4> RigidTransform::quaternion() const
{
  // The largest of the four diagonal combinations is the best conditioned to divide by.
  const std::array<double, 9>& m = r_;
  const double trace = m[0] + m[4] + m[8];
  double x, y, z, w;
  if (trace > 0.0)
  {
    const double s = 2.0 * std::sqrt(1.0 + trace);
    w = 0.25 * s;
    x = (m[7] - m[5]) / s;
    y = (m[2] - m[6]) / s;
    z = (m[3] - m[1]) / s;
  }
  else if (m[0] > m[4] && m[0] > m[8])
  {
    const double s = 2.0 * std::sqrt(1.0 + m[0] - m[4] - m[8]);
    w = (m[7] - m[5]) / s;
    x = 0.25 * s;
    y = (m[1] + m[3]) / s;
    z = (m[2] + m[6]) / s;
  }
  else if (m[4] > m[8])
  {
    const double s = 2.0 * std::sqrt(1.0 + m[4] - m[0] - m[8]);
    w = (m[2] - m[6]) / s;
    x = (m[1] + m[3]) / s;
    y = 0.25 * s;
    z = (m[5] + m[7]) / s;
  }
  else
  {
    const double s = 2.0 * std::sqrt(1.0 + m[8] - m[0] - m[4]);
    w = (m[3] - m[1]) / s;
    x = (m[2] + m[6]) / s;
    y = (m[5] + m[7]) / s;
    z = 0.25 * s;
  }
  const double sign = w < 0.0 ? -1.0 : 1.0;
  const double n = std::sqrt(x * x + y * y + z * z + w * w) * sign;
  return {x / n, y / n, z / n, w / n};
}
}  // namespace rviz_projector
