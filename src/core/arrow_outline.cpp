#include "rviz_projector/core/arrow_outline.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rviz_projector
{
namespace
{
double cross2(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b)
{
  const Vec2 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, dot(p - a, ab) / l2)) : 0.0;
  return distance(p, a + ab * t);
}

bool insideTriangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c)
{
  const double eps = 1e-12;
  return cross2(b - a, p - a) >= -eps && cross2(c - b, p - b) >= -eps && cross2(a - c, p - c) >= -eps;
}
}  // namespace

ArrowOutline::ArrowOutline(const Arrow& arrow, const ArrowDimensions& dimensions)
{
  const Vec2 along = arrow.tip - arrow.tail;
  const double length = norm(along);
  if (!std::isfinite(length) || length <= 0.0)
  {
    return;
  }
  valid_ = true;
  const Vec2 forward{along.x / length, along.y / length};  // (1 / length is Inf for a denormal length)
  const Vec2 left = perpendicular(forward);
  const double head_length = std::min(std::max(dimensions.head_length, 0.0), length);
  const Vec2 neck = arrow.tip - forward * head_length;
  const Vec2 shaft_half = left * (0.5 * std::max(dimensions.shaft_diameter, 0.0));
  const Vec2 head_half = left * (0.5 * std::max(dimensions.head_diameter, 0.0));
  corners_ = {arrow.tail - shaft_half, neck - shaft_half, neck - head_half, arrow.tip,
              neck + head_half,       neck + shaft_half, arrow.tail + shaft_half};
}

void ArrowOutline::trianglesOf(const std::vector<Arrow>& arrows, const ArrowDimensions& dimensions,
                               std::vector<Vec2>& out)
{
  out.clear();
  out.reserve(arrows.size() * kVerticesPerArrow);
  for (const Arrow& arrow : arrows)
  {
    ArrowOutline(arrow, dimensions).appendTriangles(out);
  }
}

void ArrowOutline::appendTriangles(std::vector<Vec2>& out) const
{
  if (!valid_)
  {
    return;
  }
  const auto& c = corners_;
  out.insert(out.end(), {c[0], c[1], c[5], c[0], c[5], c[6], c[2], c[3], c[4]});
}

bool ArrowOutline::contains(const Vec2& p) const
{
  if (!valid_)
  {
    return false;
  }
  const auto& c = corners_;
  return insideTriangle(p, c[0], c[1], c[5]) || insideTriangle(p, c[0], c[5], c[6]) ||
         insideTriangle(p, c[2], c[3], c[4]);
}

double ArrowOutline::distanceTo(const Vec2& p) const
{
  if (!valid_)
  {
    return std::numeric_limits<double>::infinity();
  }
  if (contains(p))
  {
    return 0.0;
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < corners_.size(); ++i)
  {
    best = std::min(best, distanceToSegment(p, corners_[i], corners_[(i + 1) % corners_.size()]));
  }
  return best;
}
}  // namespace rviz_projector
