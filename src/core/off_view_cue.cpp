#include "rviz_projector/core/off_view_cue.h"

#include <clipper.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>

#include "rviz_projector/core/angle.h"
#include "rviz_projector/core/arrow.h"
#include "rviz_projector/core/arrow_dimensions.h"
#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/path_location.h"

namespace rviz_projector
{
namespace
{
using Polygon = std::vector<Vec2>;

// Clipper works on integers: 10 micrometres, relative to the lit polygon's first vertex.
constexpr double kScale = 1e5;
constexpr double kMaxExtent = 1e6;  // metres from the first vertex: anything farther is refused

double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

double signedArea(const Polygon& polygon)
{
  double twice = 0.0;  // relative to the first vertex: far-off map coordinates lose nothing
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    twice += cross(polygon[i] - polygon[0], polygon[(i + 1) % polygon.size()] - polygon[0]);
  }
  return 0.5 * twice;
}

/// Whether closed segments ab and cd share a point.
bool segmentsTouch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d)
{
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0)))
  {
    return true;
  }
  const auto on = [](const Vec2& p, const Vec2& q, const Vec2& r, double side) {
    return side == 0.0 && std::min(p.x, q.x) <= r.x && r.x <= std::max(p.x, q.x) && std::min(p.y, q.y) <= r.y &&
           r.y <= std::max(p.y, q.y);
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

/// No two edges meet except neighbours at their shared vertex (O(n^2): a footprint has 32 points).
bool simple(const Polygon& polygon)
{
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t j = i + 1; j < n; ++j)
    {
      const bool neighbours = j == i + 1 || (i == 0 && j == n - 1);
      if (neighbours)
      {
        // Neighbours may only share their common vertex: folding back along each other is a crossing.
        const Vec2 shared = j == i + 1 ? polygon[j] : polygon[i];
        const Vec2 a = j == i + 1 ? polygon[i] : polygon[(i + 1) % n];
        const Vec2 b = j == i + 1 ? polygon[(j + 1) % n] : polygon[n - 2];
        if (cross(a - shared, b - shared) == 0.0 && dot(a - shared, b - shared) > 0.0)
        {
          return false;
        }
        continue;
      }
      if (segmentsTouch(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n]))
      {
        return false;
      }
    }
  }
  return true;
}

/// Crossing-number test (boundary points may fall either way).
bool inside(const Polygon& polygon, const Vec2& p)
{
  bool in = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
  {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x)
    {
      in = !in;
    }
  }
  return in;
}

Vec2 nearestOnSegment(const Vec2& p, const Vec2& a, const Vec2& b)
{
  const Vec2 ab = b - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0.0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
  return a + ab * t;
}

double segmentDistance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d)
{
  if (segmentsTouch(a, b, c, d))
  {
    return 0.0;
  }
  return std::min(std::min(distance(a, nearestOnSegment(a, c, d)), distance(b, nearestOnSegment(b, c, d))),
                  std::min(distance(c, nearestOnSegment(c, a, b)), distance(d, nearestOnSegment(d, a, b))));
}

bool inTriangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c)
{
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
}

/// The point of the areas nearest to p (p itself when inside one).
Vec2 nearestIn(const std::vector<Polygon>& areas, const Vec2& p)
{
  Vec2 best = p;
  double best_distance = INFINITY;
  for (const Polygon& area : areas)
  {
    if (inside(area, p))
    {
      return p;
    }
    for (std::size_t i = 0; i < area.size(); ++i)
    {
      const Vec2 q = nearestOnSegment(p, area[i], area[(i + 1) % area.size()]);
      if (distance(p, q) < best_distance)
      {
        best_distance = distance(p, q);
        best = q;
      }
    }
  }
  return best;
}

/// The polygon shrunk by `margin` (Clipper, mitred): empty when nothing is left.
std::vector<Polygon> shrink(const Polygon& polygon, double margin)
{
  if (!(margin > 0.0))
  {
    return {polygon};
  }
  const Vec2 origin = polygon.front();
  ClipperLib::Path path;
  for (const Vec2& p : polygon)
  {
    path.push_back({ClipperLib::cInt(std::llround((p.x - origin.x) * kScale)),
                    ClipperLib::cInt(std::llround((p.y - origin.y) * kScale))});
  }
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Vec2& p : polygon)
  {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  if (2.0 * margin >= std::min(x1 - x0, y1 - y0))
  {
    return {};  // nothing is left (and a huge offset would leave Clipper's integer range)
  }
  ClipperLib::ClipperOffset offset;
  offset.AddPath(path, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
  ClipperLib::Paths solution;
  try
  {
    offset.Execute(solution, -margin * kScale);
  }
  catch (const ClipperLib::clipperException&)
  {
    return {};  // cannot happen within 1e6 m and the margin check above; refused rather than thrown
  }
  std::vector<Polygon> areas;
  for (const ClipperLib::Path& piece : solution)
  {
    if (piece.size() < 3 || !ClipperLib::Orientation(piece))
    {
      continue;  // holes cannot arise from shrinking a simple polygon; skip anything odd
    }
    Polygon area;
    for (const ClipperLib::IntPoint& q : piece)
    {
      area.push_back({origin.x + double(q.X) / kScale, origin.y + double(q.Y) / kScale});
    }
    areas.push_back(area);
  }
  return areas;
}

struct Window
{
  double inside = 0.0;      ///< metres of the window's path inside the lit polygon
  bool any_inside = false;
  double last_exit = 0.0;   ///< arc length where the path last leaves the polygon within the window
};

/// The window [from, to] of the path against the polygon, exactly: each segment is cut where it
/// crosses an edge and each piece judged by its midpoint.
Window judgeWindow(const std::vector<Vec2>& points, const std::vector<double>& lengths, double from, double to,
                   const Polygon& lit)
{
  Window window;
  std::vector<double> cuts;
  // From the segment holding `from` to the one holding `to` (a 5,000-pose path: a few dozen).
  const auto first = std::upper_bound(lengths.begin(), lengths.end(), from);
  for (std::size_t i = first == lengths.begin() ? 0 : std::size_t(first - lengths.begin()) - 1;
       i + 1 < points.size() && lengths[i] < to; ++i)
  {
    const double s0 = std::max(from, lengths[i]), s1 = std::min(to, lengths[i + 1]);
    if (!(s1 > s0))
    {
      continue;
    }
    const Vec2 p = pointAtArcLength(points, lengths, s0), q = pointAtArcLength(points, lengths, s1);
    const Vec2 pq = q - p;
    cuts.assign({0.0, 1.0});
    for (std::size_t k = 0; k < lit.size(); ++k)
    {
      const Vec2& a = lit[k];
      const Vec2 ab = lit[(k + 1) % lit.size()] - a;
      const double denominator = cross(pq, ab);
      if (denominator == 0.0)
      {
        continue;  // parallel: the pieces' midpoints decide
      }
      const double t = cross(a - p, ab) / denominator, u = cross(a - p, pq) / denominator;
      if (t > 0.0 && t < 1.0 && u >= 0.0 && u <= 1.0)
      {
        cuts.push_back(t);
      }
    }
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
    {
      const double t0 = cuts[c], t1 = cuts[c + 1];
      if (!(t1 > t0))
      {
        continue;
      }
      if (inside(lit, p + pq * (0.5 * (t0 + t1))))
      {
        window.inside += (t1 - t0) * (s1 - s0);
        window.any_inside = true;
        window.last_exit = s0 + t1 * (s1 - s0);
      }
    }
  }
  return window;
}

/// The path ahead of the robot near the lit area: the segments a cue must keep clear of.
struct Band
{
  std::vector<Vec2> a, b;
  std::vector<double> clearance;
  mutable std::vector<std::size_t> near_;  // scratch of overlaps()

  void add(const Vec2& from, const Vec2& to, double keep)
  {
    a.push_back(from);
    b.push_back(to);
    clearance.push_back(keep);
  }

  bool overlaps(const std::vector<Vec2>& triangles) const
  {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const Vec2& v : triangles)
    {
      x0 = std::min(x0, v.x), y0 = std::min(y0, v.y), x1 = std::max(x1, v.x), y1 = std::max(y1, v.y);
    }
    near_.clear();  // the segments that can come within their clearance of the cue's box
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      const double keep = clearance[i];
      if (std::max(a[i].x, b[i].x) >= x0 - keep && std::min(a[i].x, b[i].x) <= x1 + keep &&
          std::max(a[i].y, b[i].y) >= y0 - keep && std::min(a[i].y, b[i].y) <= y1 + keep)
      {
        near_.push_back(i);
      }
    }
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
    {
      const Vec2& p = triangles[t];
      const Vec2& q = triangles[t + 1];
      const Vec2& r = triangles[t + 2];
      for (const std::size_t i : near_)
      {
        const double keep = clearance[i];
        if (inTriangle(a[i], p, q, r) || segmentDistance(a[i], b[i], p, q) < keep ||
            segmentDistance(a[i], b[i], q, r) < keep || segmentDistance(a[i], b[i], r, p) < keep)
        {
          return true;
        }
      }
    }
    return false;
  }
};

Band bandNear(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start, const Polygon& lit,
              double clearance)
{
  Band band;
  const double grow = std::isfinite(clearance) ? std::max(0.0, clearance) : 0.0;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Vec2& p : lit)
  {
    x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  }
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
  {
    if (lengths[i + 1] < start)
    {
      continue;
    }
    const Vec2 a = lengths[i] < start ? pointAtArcLength(points, lengths, start) : points[i];
    const Vec2& b = points[i + 1];
    if (std::max(a.x, b.x) < x0 - grow || std::min(a.x, b.x) > x1 + grow || std::max(a.y, b.y) < y0 - grow ||
        std::min(a.y, b.y) > y1 + grow)
    {
      continue;
    }
    band.add(a, b, grow);
  }
  return band;
}

/// Draws a cue moved by `shift` and scaled by `scale`.
using Shape = std::function<void(const Vec2& shift, double scale, std::vector<Vec2>& out)>;

/// The first placement (see OffViewCue) whose vertices are all inside the lit polygon and that keeps
/// clear of the band; false if none.
bool place(const Shape& shape, const Vec2& direction, const Polygon& lit, const Band& band, std::vector<Vec2>& out,
           double& scale_used, Vec2& shift_used)
{
  const Vec2 side = perpendicular(direction);
  std::vector<Vec2> candidate;
  for (const double scale : {1.0, 0.75, 0.5})
  {
    for (int back = 0; back <= 3; ++back)
    {
      for (int k = 0; k <= 24; ++k)
      {
        const int step = (k + 1) / 2 * (k % 2 == 1 ? 1 : -1);  // 0, +1, -1, +2, -2, ...
        const Vec2 shift = side * (0.05 * step) - direction * (0.1 * back);
        candidate.clear();
        shape(shift, scale, candidate);
        if (candidate.empty())
        {
          return false;
        }
        const bool within =
            std::all_of(candidate.begin(), candidate.end(), [&](const Vec2& p) { return inside(lit, p); });
        if (within && !band.overlaps(candidate))
        {
          out.insert(out.end(), candidate.begin(), candidate.end());
          scale_used = scale;
          shift_used = shift;
          return true;
        }
      }
    }
  }
  return false;
}

Vec2 centroid(const Polygon& polygon)
{
  const double area = signedArea(polygon);
  Vec2 sum;
  for (std::size_t i = 0; i < polygon.size(); ++i)
  {
    const Vec2 a = polygon[i] - polygon[0];
    const Vec2 b = polygon[(i + 1) % polygon.size()] - polygon[0];
    sum = sum + (a + b) * cross(a, b);
  }
  return polygon[0] + sum * (1.0 / (6.0 * area));
}

std::string distanceLabel(double metres)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f m", std::min(metres, 999.9));
  return text;
}
}  // namespace

const char* toString(OffViewKind kind)
{
  switch (kind)
  {
    case OffViewKind::None: return "none";
    case OffViewKind::EdgeArrow: return "edge arrow";
    case OffViewKind::TurnInPlace: return "turn in place";
    case OffViewKind::Destination: return "destination";
  }
  return "none";
}

const OffViewResult& OffViewCue::build(const std::vector<Vec2>& points, const std::vector<double>& lengths,
                                       const OffViewInput& input, const OffViewParameters& parameters)
{
  result_ = OffViewResult();
  const auto refuse = [&](const char* reason) -> const OffViewResult& {
    shown_ = false;
    result_.reason = reason;
    return result_;
  };
  if (points.size() < 2 || lengths.size() != points.size())
  {
    return refuse("no path");
  }
  if (!isFinite(input.robot) || !std::isfinite(input.heading) || !std::isfinite(input.start))
  {
    return refuse("robot pose unknown (not finite)");
  }
  if (!std::all_of(points.begin(), points.end(), isFinite) || !std::isfinite(lengths.back()))
  {
    return refuse("path has non-finite points");
  }
  if (!(parameters.arrow_length > 0.0) || !(parameters.arrow_width > 0.0) || !(parameters.glyph_size > 0.0) ||
      !std::isfinite(parameters.arrow_length + parameters.arrow_width + parameters.glyph_size))
  {
    return refuse("cue sizes must be positive and finite");
  }
  const Polygon& given = input.lit;
  if (given.size() < 3)
  {
    return refuse("no lit area (fewer than 3 points)");
  }
  for (const Vec2& p : given)
  {
    if (!isFinite(p) || std::abs(p.x - given.front().x) > kMaxExtent || std::abs(p.y - given.front().y) > kMaxExtent)
    {
      return refuse("lit area has non-finite or implausibly far points");
    }
  }
  if (!(std::abs(signedArea(given)) > 1e-6) || !simple(given))
  {
    return refuse("lit area is not a simple polygon with area");
  }
  const Polygon& lit = given;  // every test below takes either orientation (Clipper's offset too)
  const double margin = std::isfinite(parameters.margin) ? std::max(0.0, parameters.margin) : 0.0;
  const std::vector<Polygon> safe = shrink(lit, margin);
  if (safe.empty())
  {
    return refuse("lit area too small for the margin");
  }

  const double total = lengths.back();
  const double start = std::clamp(input.start, 0.0, total);
  const double look_ahead = std::isfinite(parameters.look_ahead) ? std::max(0.0, parameters.look_ahead) : 0.0;
  const double end = std::min(total, start + look_ahead);
  if (!(end - start >= 0.01))
  {
    result_.by_design = true;
    return refuse("arrived (no path ahead)");
  }
  const Window window = judgeWindow(points, lengths, start, end, lit);
  result_.visible_fraction = window.inside / (end - start);
  const double threshold = shown_ ? std::max(parameters.hide_above, parameters.show_below) : parameters.show_below;
  if (!(result_.visible_fraction < threshold))
  {
    shown_ = false;
    result_.reason = "path visible";
    result_.by_design = true;
    return result_;
  }
  shown_ = true;

  const double drawn_from = std::isfinite(input.drawn_from) ? std::clamp(input.drawn_from, 0.0, total) : 0.0;
  const Band band = bandNear(points, lengths, drawn_from, lit, parameters.path_clearance);
  const double chord = parameters.chord;
  const Vec2 forward{std::cos(input.heading), std::sin(input.heading)};
  const double path_heading = headingAt(points, lengths, start, chord);
  const double turn = std::isfinite(path_heading) ? wrapToPi(path_heading - input.heading) : 0.0;
  const double length = std::max(0.0, parameters.arrow_length);
  ArrowDimensions dimensions;
  dimensions.head_diameter = std::max(0.0, parameters.arrow_width);
  dimensions.shaft_diameter = 0.5 * dimensions.head_diameter;
  dimensions.head_length = 0.4 * length;
  const auto arrowShape = [length, dimensions](const Vec2& tip, const Vec2& direction) {
    return [=](const Vec2& shift, double scale, std::vector<Vec2>& out) {
      ArrowDimensions scaled = dimensions;
      scaled.head_diameter *= scale, scaled.shaft_diameter *= scale, scaled.head_length *= scale;
      ArrowOutline(Arrow{tip + shift - direction * (length * scale), tip + shift}, scaled).appendTriangles(out);
    };
  };

  const bool turning = std::abs(turn) > parameters.turn_angle;
  if (!turning && end >= total && inside(lit, points.back()))
  {
    // The destination's circle is lit: it shows where the robot goes (the last stretch before it
    // may lie between the robot and the lit area, with no arrows to show).
    shown_ = false;
    result_.reason = "destination visible";
    result_.by_design = true;
    return result_;
  }
  bool placed = false;
  Vec2 shift;  // of the placement found
  if (turning)
  {
    result_.kind = OffViewKind::TurnInPlace;
    result_.turn = turn > 0.0 ? TurnSide::Left : TurnSide::Right;  // wrapToPi: exactly behind is +pi
    result_.anchor = nearestIn(safe, centroid(lit));
    result_.direction = forward;
    result_.reason = result_.turn == TurnSide::Left ? "turn in place, left" : "turn in place, right";
    const Vec2 anchor = result_.anchor;
    const TurnSide side = result_.turn;
    const double size = parameters.glyph_size;
    const double heading = input.heading;
    placed = place([&](const Vec2& shift, double scale,
                       std::vector<Vec2>& out) { appendTurnGlyph(anchor + shift, heading, side, 0.0, 0.0, size * scale, out); },
                   forward, lit, band, result_.triangles, result_.scale, shift);
  }
  else if (total - start <= parameters.final_approach && !inside(lit, points.back()))
  {
    result_.kind = OffViewKind::Destination;
    const Vec2 destination = points.back();
    const Vec2 tip = nearestIn(safe, destination);
    Vec2 direction = destination - tip;
    direction = norm(direction) > 1e-9 ? direction * (1.0 / norm(direction)) : forward;
    result_.anchor = tip;
    result_.direction = direction;
    const std::string label = distanceLabel(total - start);
    const double height = std::max(0.0, parameters.digit_height);
    const Vec2 reading = perpendicular(forward);  // the robot's left
    const Vec2 up = perpendicular(reading);
    const double text_width = digitTextWidth(label, height);
    placed = place(arrowShape(tip, direction), direction, lit, band, result_.triangles, result_.scale, shift);
    if (placed)
    {
      // The label beside the placed arrow, clear of it (2 cm) and of the path; either side.
      Band clear = band;
      const std::size_t arrow_end = result_.triangles.size();
      for (std::size_t t = 0; t + 2 < arrow_end; t += 3)
      {
        for (int e = 0; e < 3; ++e)
        {
          clear.add(result_.triangles[t + e], result_.triangles[t + (e + 1) % 3], 0.02);
        }
      }
      const Vec2 middle = tip + shift - direction * (0.5 * length * result_.scale);
      const double arrow_half = 0.5 * dimensions.head_diameter * result_.scale;
      for (const double sign : {1.0, -1.0})
      {
        const Vec2 across = perpendicular(direction) * sign;
        const auto shape = [&](const Vec2& label_shift, double scale, std::vector<Vec2>& out) {
          const double half_extent =
              0.5 * scale * (text_width * std::abs(dot(across, reading)) + height * std::abs(dot(across, up)));
          const Vec2 centre = middle + label_shift + across * (arrow_half + 0.05 + half_extent);
          const Vec2 origin = centre - reading * (0.5 * text_width * scale) - up * (0.5 * height * scale);
          appendDigitTriangles(label, origin, height * scale, reading, out);
        };
        double label_scale = 1.0;
        Vec2 label_shift;
        if (place(shape, direction, lit, clear, result_.triangles, label_scale, label_shift))
        {
          result_.label = label;
          break;
        }
      }
    }
    result_.reason = placed && result_.label.empty() ? "destination " + label + " away (no room for the distance)"
                                                     : "destination " + label + " away";
  }
  else
  {
    result_.kind = OffViewKind::EdgeArrow;
    const double target_arc = window.any_inside && window.last_exit < end ? window.last_exit : end;
    const Vec2 target = pointAtArcLength(points, lengths, target_arc);
    const double heading = headingAt(points, lengths, target_arc, chord);
    const Vec2 direction = std::isfinite(heading) ? Vec2{std::cos(heading), std::sin(heading)} : forward;
    result_.anchor = nearestIn(safe, target);
    result_.direction = direction;
    result_.reason = "path leaves the lit area";
    placed = place(arrowShape(result_.anchor, direction), direction, lit, band, result_.triangles, result_.scale, shift);
  }
  result_.anchor = result_.anchor + shift;
  if (!placed)
  {
    result_.triangles.clear();
    result_.label.clear();
    result_.reason += " (no room clear of the visible path)";
  }
  return result_;
}
}  // namespace rviz_projector
