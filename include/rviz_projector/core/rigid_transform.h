// Rotation + translation taking points from one frame into another (p_parent = R * p_child + t).
#pragma once

#include <array>

#include "rviz_projector/core/vec3.h"

namespace rviz_projector
{
class RigidTransform
{
public:
  /// Identity transform.
  RigidTransform() = default;
  /// From a unit quaternion (x, y, z, w; normalised here) and a translation.
  static RigidTransform fromQuaternion(double qx, double qy, double qz, double qw, const Vec3& translation);

  /// From a row-major rotation matrix (taken as it is: it must be a rotation) and a translation.
  static RigidTransform fromMatrix(const std::array<double, 9>& rotation, const Vec3& translation);

  /// The rotation as a unit quaternion {x, y, z, w} (w >= 0).
  std::array<double, 4> quaternion() const;
  Vec3 apply(const Vec3& p) const;
  /// Rotates a direction (no translation).
  Vec3 rotate(const Vec3& d) const;
  /// This transform after `b_T_c`: with this = a_T_b, the result is a_T_c (apply b_T_c first).
  RigidTransform operator*(const RigidTransform& b_T_c) const;
  /// b_T_a for this = a_T_b (the rotation transposed).
  RigidTransform inverse() const;
  const Vec3& translation() const { return t_; }
  /// Row-major rotation matrix.
  const std::array<double, 9>& rotation() const { return r_; }

private:
  std::array<double, 9> r_{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 t_;
};
}  // namespace rviz_projector
