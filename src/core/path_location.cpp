#include "rviz_projector/core/path_location.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
void accumulateArcLengths(const std::vector<Vec2>& points, std::vector<double>& lengths)
{
  lengths.resize(points.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (i > 0)
    {
      sum += distance(points[i - 1], points[i]);
    }
    lengths[i] = sum;
  }
}

PathLocation locateOnPath(const std::vector<Vec2>& points, const std::vector<double>& lengths, const Vec2& p)
{
  PathLocation best;
  if (points.empty() || lengths.size() != points.size() || !isFinite(p))
  {
    return best;
  }
  constexpr double kTie = 1e-9;
  best.valid = true;
  best.point = points.front();
  best.arc_length = 0.0;
  best.distance = distance(p, points.front());
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
  {
    const Vec2 a = points[i];
    const Vec2 ab = points[i + 1] - a;
    const double length_squared = dot(ab, ab);
    const double t = length_squared > 0.0 ? std::clamp(dot(p - a, ab) / length_squared, 0.0, 1.0) : 0.0;
    const Vec2 q = a + ab * t;
    const double d = distance(p, q);
    if (d < best.distance - kTie)  // strictly nearer: ties keep the earlier (smaller arc length) place
    {
      best.distance = d;
      best.point = q;
      best.arc_length = lengths[i] + (lengths[i + 1] - lengths[i]) * t;
    }
  }
  return best;
}

Vec2 pointAtArcLength(const std::vector<Vec2>& points, const std::vector<double>& lengths, double s)
{
  if (points.empty() || lengths.size() != points.size())
  {
    return Vec2();
  }
  if (!(s > 0.0))
  {
    return points.front();  // also NaN
  }
  if (s >= lengths.back())
  {
    return points.back();
  }
  // The first point whose arc length exceeds s: the segment before it holds s.
  const auto it = std::upper_bound(lengths.begin(), lengths.end(), s);
  const std::size_t j = static_cast<std::size_t>(it - lengths.begin());
  const std::size_t i = j - 1;
  const double segment = lengths[j] - lengths[i];
  const double t = segment > 0.0 ? (s - lengths[i]) / segment : 0.0;
  return points[i] + (points[j] - points[i]) * t;
}

double headingAt(const std::vector<Vec2>& points, const std::vector<double>& lengths, double s, double chord)
{
  if (points.size() < 2 || lengths.size() != points.size() || !(lengths.back() > 1e-9))
  {
    return std::nan("");
  }
  const double total = lengths.back();
  double from = std::isfinite(s) ? std::clamp(s, 0.0, total) : 0.0;
  const double length = std::isfinite(chord) && chord > 0.0 ? chord : 1e-3;
  double to = from + length;
  if (to > total)
  {
    to = total;
    from = std::max(0.0, total - length);
  }
  const Vec2 d = pointAtArcLength(points, lengths, to) - pointAtArcLength(points, lengths, from);
  if (!(norm(d) > 0.0))
  {
    return std::nan("");
  }
  return std::atan2(d.y, d.x);
}
}  // namespace rviz_projector
