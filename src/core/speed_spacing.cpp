#include "rviz_projector/core/speed_spacing.h"

#include <algorithm>
#include <cmath>

#include "rviz_projector/core/path_style_limits.h"

namespace rviz_projector
{
namespace
{
double finiteOr(double value, double fallback, double lowest)
{
  return std::isfinite(value) && value >= lowest ? value : fallback;
}
}  // namespace

double plannedSpeed(const SpeedCoding& coding, double from_end)
{
  const double speed = finiteOr(coding.speed, 0.0, 0.0);
  const double deceleration = std::isfinite(coding.deceleration) && coding.deceleration > 0.0 ? coding.deceleration : 0.5;
  const double distance = std::isfinite(from_end) && from_end > 0.0 ? from_end : 0.0;
  return std::min(speed, std::sqrt(2.0 * deceleration * distance));
}

double speedCodedSpacing(const SpeedCoding& coding, double from_end)
{
  const double time_step = finiteOr(coding.time_step, 0.5, 0.0);
  const double min_spacing =
      std::clamp(finiteOr(coding.min_spacing, path_style::kMinSpacing, 0.0), path_style::kMinSpacing, path_style::kMaxSpacing);
  const double spacing = plannedSpeed(coding, from_end) * time_step;
  return std::clamp(std::isfinite(spacing) ? spacing : min_spacing, min_spacing, path_style::kMaxSpacing);
}
}  // namespace rviz_projector
