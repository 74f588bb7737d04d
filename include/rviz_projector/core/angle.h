// Angles: the one wrap function of the core.
#pragma once

#include <cmath>

namespace rviz_projector
{
/// `angle` (radians) wrapped into (-pi, pi].
inline double wrapToPi(double angle)
{
  constexpr double kPi = 3.14159265358979323846;
  const double r = std::remainder(angle, 2.0 * kPi);  // in [-pi, pi]
  return r <= -kPi ? r + 2.0 * kPi : r;
}
}  // namespace rviz_projector
