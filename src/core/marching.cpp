#include "rviz_projector/core/marching.h"

#include <cmath>

namespace rviz_projector
{
double marchingPhase(double speed, double time, double spacing)
{
  if (!std::isfinite(speed) || !std::isfinite(time) || !std::isfinite(spacing) || !(speed > 0.0) || !(spacing > 0.0))
  {
    return 0.0;
  }
  double phase = std::fmod(-speed * time, spacing);
  if (phase < 0.0)
  {
    phase += spacing;
  }
  return phase < spacing ? phase : 0.0;
}
}  // namespace rviz_projector
