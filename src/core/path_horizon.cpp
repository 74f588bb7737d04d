#include "rviz_projector/core/path_horizon.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
double HorizonWindow::alpha(double s) const
{
  if (!enabled)
  {
    return 1.0;
  }
  if (!std::isfinite(s) || s < start || s >= end)
  {
    return 0.0;
  }
  if (fade > 0.0 && s > end - fade)
  {
    return (end - s) / fade;
  }
  return 1.0;
}

HorizonWindow makeHorizon(double robot_arc_length, double horizon_length, double fade_length)
{
  const auto nonNegative = [](double v) { return std::isfinite(v) && v > 0.0 ? v : 0.0; };
  HorizonWindow window;
  window.enabled = true;
  window.start = nonNegative(robot_arc_length);
  const double length = nonNegative(horizon_length);
  window.end = window.start + length;
  window.fade = std::min(nonNegative(fade_length), length);
  return window;
}
}  // namespace rviz_projector
