#include "rviz_projector/core/scan_simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rviz_projector
{
void simulateScan(const ScanGeometry& geometry, const Vec2& origin, double yaw, const std::vector<Circle>& circles,
                  std::vector<float>& ranges)
{
  const int beams = std::max(0, geometry.beams);
  ranges.assign(static_cast<std::size_t>(beams), std::numeric_limits<float>::infinity());
  if (!isFinite(origin) || !std::isfinite(yaw) || !std::isfinite(geometry.angle_min) ||
      !std::isfinite(geometry.angle_increment) || !std::isfinite(geometry.range_max))
  {
    return;
  }
  for (int i = 0; i < beams; ++i)
  {
    const double angle = yaw + geometry.angle_min + i * geometry.angle_increment;
    const Vec2 direction{std::cos(angle), std::sin(angle)};
    double nearest = std::numeric_limits<double>::infinity();
    for (const Circle& circle : circles)
    {
      if (!isFinite(circle.centre) || !(circle.radius > 0.0))
      {
        continue;
      }
      // |origin + t d - c|^2 = r^2  ->  t^2 - 2 t (d.(c - o)) + |c - o|^2 - r^2 = 0
      const Vec2 to_centre = circle.centre - origin;
      const double along = dot(direction, to_centre);
      const double c = dot(to_centre, to_centre) - circle.radius * circle.radius;
      if (c <= 0.0)
      {
        nearest = std::min(nearest, geometry.range_min);  // inside the circle
        continue;
      }
      const double discriminant = along * along - c;
      if (discriminant < 0.0 || along <= 0.0)
      {
        continue;  // missed, or behind the scanner
      }
      nearest = std::min(nearest, along - std::sqrt(discriminant));
    }
    if (nearest <= geometry.range_max)
    {
      ranges[static_cast<std::size_t>(i)] = static_cast<float>(std::max(nearest, geometry.range_min));
    }
  }
}
}  // namespace rviz_projector
