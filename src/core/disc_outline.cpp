#include "rviz_projector/core/disc_outline.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
DiscOutline::DiscOutline(const Vec2& centre, double diameter, int segments)
  : centre_(centre)
  , radius_(std::isfinite(diameter) ? std::max(0.5 * diameter, 0.0) : 0.0)
  , segments_(std::max(segments, 3))
{
}

void DiscOutline::appendTriangles(std::vector<Vec2>& out) const
{
  if (radius_ <= 0.0 || !isFinite(centre_))
  {
    return;
  }
  const double step = 2.0 * M_PI / segments_;
  Vec2 previous{centre_.x + radius_, centre_.y};
  for (int i = 1; i <= segments_; ++i)
  {
    const double angle = step * i;
    const Vec2 next{centre_.x + radius_ * std::cos(angle), centre_.y + radius_ * std::sin(angle)};
    out.insert(out.end(), {centre_, previous, next});
    previous = next;
  }
}

bool DiscOutline::contains(const Vec2& p) const
{
  return distance(p, centre_) <= radius_;
}
}  // namespace rviz_projector
