#include "rviz_projector/core/turn_signal.h"

#include "rviz_projector/core/angle.h"

#include <algorithm>
#include <cmath>

#include "rviz_projector/core/path_location.h"

namespace rviz_projector
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

double cross(const Vec2& a, const Vec2& b)
{
  return a.x * b.y - a.y * b.x;
}

/// Appends triangle a, b, c counter-clockwise seen from above (reordered when needed).
void appendTriangle(const Vec2& a, const Vec2& b, const Vec2& c, std::vector<Vec2>& out)
{
  if (cross(b - a, c - a) < 0.0)
  {
    out.insert(out.end(), {a, c, b});
  }
  else
  {
    out.insert(out.end(), {a, b, c});
  }
}

void appendQuad(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, std::vector<Vec2>& out)
{
  appendTriangle(a, b, c, out);
  appendTriangle(a, c, d, out);
}
}  // namespace

TurnDetection detectTurn(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start,
                         const TurnSignalParameters& parameters)
{
  TurnDetection result;
  result.heading = std::nan("");
  if (points.size() < 2 || lengths.size() != points.size() || !std::isfinite(start) ||
      !std::isfinite(parameters.angle) || !std::isfinite(parameters.distance) || !(parameters.step > 0.0) ||
      !std::isfinite(parameters.step))
  {
    return result;
  }
  const double total = lengths.back();
  const double from = std::clamp(start, 0.0, total);
  result.heading = headingAt(points, lengths, from, parameters.chord);
  if (!std::isfinite(result.heading))
  {
    return result;
  }
  const double last = std::min(total, from + std::max(0.0, parameters.distance));
  double previous = result.heading;
  double sum = 0.0;
  // Bounded: at most distance / step samples (a huge distance is cut by the path's length).
  const std::size_t samples = static_cast<std::size_t>(std::min(1e6, std::floor((last - from) / parameters.step)));
  for (std::size_t i = 1; i <= samples; ++i)
  {
    const double ahead = static_cast<double>(i) * parameters.step;
    const double heading = headingAt(points, lengths, from + ahead, parameters.chord);
    if (!std::isfinite(heading))
    {
      continue;
    }
    sum += wrapToPi(heading - previous);
    previous = heading;
    if (std::abs(sum) > parameters.angle)
    {
      result.side = sum > 0.0 ? TurnSide::Left : TurnSide::Right;
      result.ahead = ahead;
      return result;
    }
  }
  return result;
}

void appendTurnGlyph(const Vec2& robot, double heading, TurnSide side, double ahead, double aside, double size,
                     std::vector<Vec2>& triangles)
{
  if (side == TurnSide::None || !isFinite(robot) || !std::isfinite(heading) || !std::isfinite(ahead) ||
      !std::isfinite(aside) ||
      !std::isfinite(size) || !(size > 0.0))
  {
    return;
  }
  const Vec2 forward{std::cos(heading), std::sin(heading)};
  const Vec2 toward = side == TurnSide::Left ? perpendicular(forward) : perpendicular(forward) * -1.0;
  const Vec2 centre = robot + forward * ahead + toward * aside;
  // Local coordinates: u along `forward`, v towards the turn. The band is a quarter circle of
  // radius R about (0, R): it starts at (0, 0) heading +u and ends at (R, R) heading +v, where the
  // head (width 2.2 w, length 0.45 size) points on along +v. The shape's box is centred on `centre`.
  const double width = size / 5.0;
  const double radius = 0.5 * size;
  const double head_length = 0.45 * size;
  const double head_half = 1.1 * width;
  const double u_min = -0.0, u_max = radius + head_half;
  const double v_min = -0.5 * width, v_max = radius + head_length;
  const double uc = 0.5 * (u_min + u_max), vc = 0.5 * (v_min + v_max);
  const auto world = [&](double u, double v) { return centre + forward * (u - uc) + toward * (v - vc); };
  constexpr int kSegments = 12;
  for (int i = 0; i < kSegments; ++i)
  {
    const double a0 = 0.5 * kPi * i / kSegments, a1 = 0.5 * kPi * (i + 1) / kSegments;
    const double inner = radius - 0.5 * width, outer = radius + 0.5 * width;
    const auto on = [&](double r, double a) { return world(r * std::sin(a), radius - r * std::cos(a)); };
    appendQuad(on(outer, a0), on(outer, a1), on(inner, a1), on(inner, a0), triangles);
  }
  appendTriangle(world(radius - head_half, radius), world(radius + head_half, radius),
                 world(radius, radius + head_length), triangles);
}

void appendCross(const Vec2& centre, double size, double width, std::vector<Vec2>& triangles)
{
  if (!isFinite(centre) || !std::isfinite(size) || !std::isfinite(width) || !(size > 0.0) || !(width > 0.0))
  {
    return;
  }
  const double half = 0.5 * size;
  const double w = 0.5 * width;
  for (const Vec2& axis : {Vec2{M_SQRT1_2, M_SQRT1_2}, Vec2{M_SQRT1_2, -M_SQRT1_2}})
  {
    const Vec2 across = perpendicular(axis);
    appendQuad(centre - axis * half - across * w, centre + axis * half - across * w, centre + axis * half + across * w,
               centre - axis * half + across * w, triangles);
  }
}
}  // namespace rviz_projector
