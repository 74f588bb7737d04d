#include "rviz_projector/core/acknowledge_arc.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
namespace
{
double cross(const Vec2& a, const Vec2& b)
{
  return a.x * b.y - a.y * b.x;
}

bool sane(double v)
{
  return std::isfinite(v) && std::abs(v) <= kAcknowledgeMaxMetres;
}

bool sane(const Vec2& p)
{
  return sane(p.x) && sane(p.y);
}

/// Appends a, b, c counter-clockwise seen from above (swapped when clockwise).
void triangle(std::vector<Vec2>& out, const Vec2& a, const Vec2& b, const Vec2& c)
{
  out.push_back(a);
  if (cross(b - a, c - a) >= 0.0)
  {
    out.push_back(b);
    out.push_back(c);
  }
  else
  {
    out.push_back(c);
    out.push_back(b);
  }
}

Vec2 polar(const Vec2& centre, double radius, double angle)
{
  return {centre.x + radius * std::cos(angle), centre.y + radius * std::sin(angle)};
}

struct AheadPoint
{
  double distance = 0.0;
  Vec2 point;
  Vec2 direction;  ///< of the segment it lies on (unit; zero for a single-point path)
};

/// The point of segment [a, b] nearest p.
Vec2 nearestOnSegment(const Vec2& a, const Vec2& b, const Vec2& p)
{
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  const double t = len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return a + ab * t;
}

double squared(const Vec2& a)
{
  return dot(a, a);
}

/// The nearest point to `p` of the path from `start` onward (squared distances in the loop; the
/// direction only for the best segment).
AheadPoint nearestAhead(const std::vector<Vec2>& path, const PathAheadStart& start, const Vec2& p)
{
  Vec2 best_point = start.point;
  double best = squared(p - start.point);
  std::size_t best_segment = path.size();  // none yet: a single point, or only zero-length segments
  for (std::size_t i = start.segment; i + 1 < path.size(); ++i)
  {
    const Vec2 a = i == start.segment ? start.point : path[i];
    const Vec2& b = path[i + 1];
    if (path[i].x == b.x && path[i].y == b.y)
    {
      continue;
    }
    const Vec2 q = nearestOnSegment(a, b, p);
    const double d = squared(p - q);
    if (d < best || (best_segment == path.size() && d <= best))
    {
      best = d;
      best_point = q;
      best_segment = i;
    }
  }
  AheadPoint out;
  out.point = best_point;
  out.distance = std::sqrt(best);
  if (best_segment < path.size())
  {
    const Vec2 along = path[best_segment + 1] - path[best_segment];
    out.direction = along * (1.0 / norm(along));
  }
  return out;
}

AcknowledgeResult refused(const char* why)
{
  AcknowledgeResult r;
  r.reason = why;
  return r;
}

void sideArrow(const Vec2& person, double radius, const Vec2& direction, int side, double width,
               std::vector<Vec2>& out)
{
  // The side the path is on, seen from the person: -side x the path's left normal. The arrow's
  // centre line runs along the path's direction 2 x width beyond `radius`: its shaft (width wide)
  // and its head (3 x width wide) stay at least width / 2 beyond `radius`.
  const Vec2 towards_path = perpendicular(direction) * static_cast<double>(-side);
  const Vec2 centre = person + towards_path * (radius + 2.0 * width);
  const Vec2 tail = centre - direction * (0.5 * kSideArrowLength);
  const Vec2 tip = centre + direction * (0.5 * kSideArrowLength);
  const Vec2 neck = tip - direction * std::min(3.0 * width, 0.5 * kSideArrowLength);
  const Vec2 half = towards_path * (0.5 * width);
  triangle(out, tail - half, neck - half, neck + half);
  triangle(out, tail - half, neck + half, tail + half);
  const Vec2 wing = towards_path * (1.5 * width);
  triangle(out, neck - wing, tip, neck + wing);
}
}  // namespace

PathAheadStart locatePathAhead(const std::vector<Vec2>& path, const Vec2& robot)
{
  PathAheadStart start;
  if (path.empty())
  {
    start.problem = "no path";
    return start;
  }
  for (const Vec2& q : path)
  {
    if (!sane(q))
    {
      start.problem = "the path has NaN/Inf or too distant points";
      return start;
    }
  }
  if (!sane(robot))
  {
    start.problem = "the person's or the robot's place is NaN/Inf or too far";
    return start;
  }
  // The first segment (and its point) nearest the robot.
  start.point = path.front();
  double best = squared(robot - start.point);
  for (std::size_t i = 0; i + 1 < path.size(); ++i)
  {
    const Vec2 q = nearestOnSegment(path[i], path[i + 1], robot);
    const double d = squared(robot - q);
    if (d < best)
    {
      best = d;
      start.segment = i;
      start.point = q;
    }
  }
  start.valid = true;
  return start;
}

AcknowledgeResult acknowledgeArc(const Vec2& person, double feet_radius, const Vec2& robot,
                                 const std::vector<Vec2>& path, const AcknowledgeParameters& parameters,
                                 std::vector<Vec2>& triangles)
{
  return acknowledgeArc(person, feet_radius, robot, path, locatePathAhead(path, robot), parameters, triangles);
}

AcknowledgeResult acknowledgeArc(const Vec2& person, double feet_radius, const Vec2& robot,
                                 const std::vector<Vec2>& path, const PathAheadStart& start,
                                 const AcknowledgeParameters& parameters, std::vector<Vec2>& triangles)
{
  const AcknowledgeParameters& p = parameters;
  if (!sane(person) || !sane(robot) || !sane(feet_radius) || feet_radius < 0.0)
  {
    return refused("the person's or the robot's place is NaN/Inf or too far");
  }
  if (!start.valid || start.segment >= path.size())
  {
    return refused(start.problem.empty() ? "no path" : start.problem.c_str());
  }
  if (!sane(p.range) || !sane(p.distance) || !sane(p.line_width) || !std::isfinite(p.arc_angle) ||
      !(p.line_width > 0.0) || !(p.arc_angle > 0.0) || p.distance < 0.0 || p.range < 0.0)
  {
    return refused("unusable Range, Distance, Arc angle or Line width");
  }
  const AheadPoint ahead = nearestAhead(path, start, person);
  AcknowledgeResult r;
  r.path_distance = ahead.distance;
  r.closest = ahead.point;
  if (!(ahead.distance <= p.range))
  {
    r.reason = "out of Range of the path ahead";
    return r;
  }
  const Vec2 to_robot = robot - person;
  if (norm(to_robot) <= 1e-9)
  {
    r.reason = "the robot is on the person";
    return r;
  }
  const double c = cross(ahead.direction, person - ahead.point);
  r.side = ahead.distance > 1e-9 && (ahead.direction.x != 0.0 || ahead.direction.y != 0.0) ? (c > 0.0 ? 1 : (c < 0.0 ? -1 : 0)) : 0;
  r.inner_radius = feet_radius + p.distance;
  r.outer_radius = r.inner_radius + p.line_width;
  const double angle = std::min(p.arc_angle, 2.0 * M_PI);
  const double mid = std::atan2(to_robot.y, to_robot.x);
  const int steps = std::max(2, static_cast<int>(std::ceil(angle / kAcknowledgeArcStep)));
  for (int i = 0; i < steps; ++i)
  {
    const double a0 = mid - 0.5 * angle + angle * i / steps;
    const double a1 = mid - 0.5 * angle + angle * (i + 1) / steps;
    const Vec2 i0 = polar(person, r.inner_radius, a0), i1 = polar(person, r.inner_radius, a1);
    const Vec2 o0 = polar(person, r.outer_radius, a0), o1 = polar(person, r.outer_radius, a1);
    triangle(triangles, i0, o0, o1);
    triangle(triangles, i0, o1, i1);
  }
  if (p.side_arrow && r.side != 0)
  {
    sideArrow(person, r.outer_radius, ahead.direction, r.side, p.line_width, triangles);
  }
  r.drawn = true;
  return r;
}
}  // namespace rviz_projector
