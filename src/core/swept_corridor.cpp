#include "rviz_projector/core/swept_corridor.h"

#include <clipper.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "rviz_projector/core/path_location.h"
#include "rviz_projector/core/polygon_triangulation.h"

namespace rviz_projector
{
namespace
{
// Clipper works on integers: 10 micrometres, relative to the corridor's first position (so map
// coordinates far from the origin lose nothing).
constexpr double kScale = 1e5;
// Vertices of the union closer than this (0.5 mm) are merged, near-collinear ones dropped.
constexpr double kCleanDistance = 0.0005 * kScale;

double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

bool segmentsCross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d)
{
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

using Placement = SweptCorridor::Placement;

Vec2 place(const Placement& at, const Vec2& v)
{
  return at.position + at.forward * v.x + perpendicular(at.forward) * v.y;
}

ClipperLib::IntPoint toClipper(const Vec2& v)
{
  return {ClipperLib::cInt(std::llround(v.x * kScale)), ClipperLib::cInt(std::llround(v.y * kScale))};
}

Vec2 fromClipper(const ClipperLib::IntPoint& p, const Vec2& origin)
{
  return {origin.x + double(p.X) / kScale, origin.y + double(p.Y) / kScale};
}

/// Triangles of width `width` centred on the polyline (miter joins, limited to twice the half width).
void thickLine(const std::vector<Vec2>& line, bool closed, double width, std::vector<Vec2>& out)
{
  const std::size_t n = line.size();
  if (n < 2)
  {
    return;
  }
  auto normal = [&](std::size_t i) {  // left normal of segment i -> i + 1
    const Vec2 d = line[(i + 1) % n] - line[i];
    const double length = norm(d);
    return length > 0 ? perpendicular(d) * (1.0 / length) : Vec2{};
  };
  const double half = 0.5 * width;
  std::vector<Vec2> offset(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const bool has_before = closed || i > 0, has_after = closed || i + 1 < n;
    const Vec2 before = has_before ? normal((i + n - 1) % n) : normal(i);
    const Vec2 after = has_after ? normal(i) : before;
    Vec2 miter = before + after;
    const double length = norm(miter);
    miter = length > 1e-9 ? miter * (1.0 / length) : after;
    const double cosine = std::max(dot(miter, after), 0.5);
    offset[i] = miter * (half / cosine);
  }
  const std::size_t segments = closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i)
  {
    const std::size_t j = (i + 1) % n;
    const Vec2 a = line[i] + offset[i], b = line[i] - offset[i], c = line[j] + offset[j], d = line[j] - offset[j];
    out.insert(out.end(), {a, b, d, a, d, c});
  }
}

/// The footprint vertex farthest to one side (`side` +1: left, -1: right); ties (1 mm) go to the
/// rearmost (`rear`) or the foremost vertex.
Vec2 sideVertex(const std::vector<Vec2>& footprint, double side, bool rear)
{
  double extreme = -INFINITY;
  for (const Vec2& v : footprint) extreme = std::max(extreme, side * v.y);
  Vec2 best{NAN, NAN};
  for (const Vec2& v : footprint)
  {
    if (side * v.y >= extreme - 1e-3 && (std::isnan(best.x) || (rear ? v.x < best.x : v.x > best.x)))
    {
      best = v;
    }
  }
  return best;
}

std::size_t nearestIndex(const std::vector<Vec2>& ring, const Vec2& p)
{
  std::size_t best = 0;
  double best_distance = INFINITY;
  for (std::size_t i = 0; i < ring.size(); ++i)
  {
    const double d = distance(ring[i], p);
    if (d < best_distance)
    {
      best_distance = d;
      best = i;
    }
  }
  return best;
}

/// Clipper's paths back in metres (the corridor's origin added), cleaned first.
std::vector<std::vector<Vec2>> fromClipper(ClipperLib::Paths paths, const Vec2& origin)
{
  ClipperLib::CleanPolygons(paths, kCleanDistance);
  std::vector<std::vector<Vec2>> rims;
  for (const ClipperLib::Path& path : paths)
  {
    rims.emplace_back();
    for (const ClipperLib::IntPoint& p : path)
    {
      rims.back().push_back(fromClipper(p, origin));
    }
  }
  return rims;
}
}  // namespace

std::vector<Vec2> parseFootprint(const std::string& text, std::string& error)
{
  // Numbers and brackets only: "[[x, y], ...]", nested exactly two deep, pairs of numbers.
  std::vector<Vec2> polygon;
  std::vector<double> pair;
  int depth = 0;
  error.clear();
  for (std::size_t i = 0; i < text.size() && error.empty();)
  {
    const char c = text[i];
    if (c == '[')
    {
      if (++depth > 2)
      {
        error = "more than two levels of brackets";
      }
      pair.clear();
      ++i;
    }
    else if (c == ']')
    {
      if (depth == 2)
      {
        if (pair.size() != 2)
        {
          error = "point " + std::to_string(polygon.size() + 1) + " has " + std::to_string(pair.size()) +
                  " numbers (x and y are needed)";
        }
        else
        {
          polygon.push_back({pair[0], pair[1]});
        }
      }
      if (--depth < 0)
      {
        error = "a ']' without its '['";
      }
      ++i;
    }
    else if (c == ',' || c == ' ' || c == '\t' || c == '\n')
    {
      ++i;
    }
    else
    {
      const char* begin = text.c_str() + i;
      char* end = nullptr;
      const double value = std::strtod(begin, &end);
      if (end == begin || depth != 2)
      {
        error = "unexpected '" + text.substr(i, 12) + "'";
      }
      else
      {
        pair.push_back(value);
        i += std::size_t(end - begin);
      }
    }
  }
  if (error.empty() && depth != 0)
  {
    error = "a '[' without its ']'";
  }
  if (error.empty() && polygon.empty())
  {
    error = "no points";
  }
  if (!error.empty())
  {
    error = "cannot read the footprint \"" + text + "\": " + error + " (write [[x, y], [x, y], ...] in metres)";
    polygon.clear();
  }
  return polygon;
}

std::string footprintProblem(const std::vector<Vec2>& footprint)
{
  if (footprint.size() < 3)
  {
    return "the footprint has " + std::to_string(footprint.size()) + " points (at least 3 are needed)";
  }
  for (const Vec2& v : footprint)
  {
    if (!isFinite(v))
    {
      return "the footprint has a point that is not a finite number";
    }
  }
  if (std::abs(signedArea(footprint)) < 1e-6)
  {
    return "the footprint has no area";
  }
  const std::size_t n = footprint.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t j = i + 2; j < n; ++j)
    {
      if ((j + 1) % n != i && segmentsCross(footprint[i], footprint[(i + 1) % n], footprint[j], footprint[(j + 1) % n]))
      {
        return "the footprint's edges cross (edges " + std::to_string(i + 1) + " and " + std::to_string(j + 1) + ")";
      }
    }
  }
  return "";
}

namespace
{
/// The positions the footprint is placed at: every `step` metres of path from `from` to `to`, more
/// where the heading turns faster than `turn_step`; relative to `origin`.
std::vector<Placement> placementsAlong(const std::vector<Vec2>& points, const std::vector<double>& lengths, double from,
                                       double to, const Vec2& origin, const CorridorParameters& parameters)
{
  std::vector<Placement> placements;
  // The heading at s is that of a chord centred on s (headingAt's chord starts at s).
  auto headingOf = [&](double s) {
    return headingAt(points, lengths, std::max(0.0, s - 0.5 * parameters.heading_chord), parameters.heading_chord);
  };
  auto placementAt = [&](double s, double heading) {
    return Placement{pointAtArcLength(points, lengths, s) - origin, {std::cos(heading), std::sin(heading)}};
  };
  double previous_s = from;
  double previous_heading = headingOf(from);
  if (!std::isfinite(previous_heading))
  {
    return placements;
  }
  placements.push_back(placementAt(from, previous_heading));
  const double steps_wanted = std::ceil((to - from) / parameters.step);
  if (!(steps_wanted <= 100000.0))
  {
    return placements;  // over 100,000 positions: a step or a length that makes no sense
  }
  const int steps = int(steps_wanted);
  for (int i = 1; i <= steps; ++i)
  {
    const double s = from + (to - from) * i / steps;
    const double heading = headingOf(s);
    if (!std::isfinite(heading))
    {
      return {};
    }
    const double turn = std::remainder(heading - previous_heading, 2.0 * M_PI);
    const int parts = int(std::clamp(std::ceil(std::abs(turn) / parameters.turn_step), 1.0, 360.0));
    for (int k = 1; k <= parts; ++k)
    {
      const double f = double(k) / parts;
      placements.push_back(placementAt(previous_s + (s - previous_s) * f, previous_heading + turn * f));
    }
    previous_s = s;
    previous_heading = heading;
  }
  return placements;
}

/// Whether the counter-clockwise polygon is convex (no vertex turns right; straight ones allowed).
bool isConvex(const std::vector<Vec2>& ccw)
{
  const std::size_t n = ccw.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    if (cross(ccw[(i + 1) % n] - ccw[i], ccw[(i + 2) % n] - ccw[(i + 1) % n]) < 0.0)
    {
      return false;
    }
  }
  return true;
}

/// The last placement from `first` on that the footprint reaches by translation alone: the same
/// heading (within 1e-9 rad) and every position further along the line of the first step (within
/// 1 um of it, a tenth of Clipper's grid); `first` itself when the next step turns.
std::size_t translationEnd(const std::vector<Placement>& placements, std::size_t first)
{
  const Placement& from = placements[first];
  if (first + 1 >= placements.size())
  {
    return first;
  }
  const Vec2 step = placements[first + 1].position - from.position;
  const double length = norm(step);
  if (!(length > 0.0))
  {
    return first;
  }
  const Vec2 along = step * (1.0 / length);
  std::size_t last = first;
  for (std::size_t k = first + 1; k < placements.size(); ++k)
  {
    const Placement& to = placements[k];
    const bool same_heading = std::abs(cross(from.forward, to.forward)) < 1e-9 && dot(from.forward, to.forward) > 0.0;
    const bool on_line = std::abs(cross(along, to.position - from.position)) < 1e-6;
    const bool onwards = dot(along, to.position - placements[k - 1].position) > 0.0;
    if (!(same_heading && on_line && onwards))
    {
      break;
    }
    last = k;
  }
  return last;
}

/// The area a convex counter-clockwise footprint sweeps moving without turning from `from` to
/// `to` (same heading): the convex hull of its two places, counter-clockwise. Its rim is the
/// footprint's front at `to` and its back at `from`, joined at the two vertices farthest to either
/// side of the motion.
std::vector<Vec2> translationHull(const std::vector<Vec2>& footprint, const Placement& from, const Placement& to)
{
  const std::size_t n = footprint.size();
  const Vec2 motion = to.position - from.position;
  std::vector<Vec2> placed(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    placed[i] = place(from, footprint[i]);
  }
  if (!(norm(motion) > 0.0))
  {
    return placed;
  }
  std::size_t left = 0, right = 0;  // the vertices farthest left and right of the motion
  for (std::size_t i = 1; i < n; ++i)
  {
    if (cross(motion, placed[i]) > cross(motion, placed[left])) left = i;
    if (cross(motion, placed[i]) < cross(motion, placed[right])) right = i;
  }
  std::vector<Vec2> hull;
  // Counter-clockwise from the right one to the left one the rim faces forward (moved to `to`),
  // from the left one back to the right one it faces backward (stays at `from`).
  for (std::size_t i = right;; i = (i + 1) % n)
  {
    hull.push_back(placed[i] + motion);
    if (i == left) break;
  }
  for (std::size_t i = left;; i = (i + 1) % n)
  {
    hull.push_back(placed[i]);
    if (i == right) break;
  }
  return hull;
}

/// Pieces of the swept area, counter-clockwise, for Clipper's union.
class Pieces
{
public:
  explicit Pieces(const Vec2& origin) : origin_(origin) {}

  /// A triangle (nothing when it has no area).
  void add(const Vec2& a, const Vec2& b, const Vec2& c)  // corridor coordinates
  {
    if (std::abs(cross(b - a, c - a)) >= 1e-14)
    {
      addPolygon({a, b, c});
    }
  }

  /// A simple polygon, in either orientation.
  void addPolygon(const std::vector<Vec2>& polygon)
  {
    ClipperLib::Path piece;
    for (const Vec2& v : polygon)
    {
      piece.push_back(toClipper(v));
    }
    if (!ClipperLib::Orientation(piece))
    {
      std::reverse(piece.begin(), piece.end());  // all counter-clockwise: non-zero winding adds them up
    }
    paths_.push_back(std::move(piece));
  }

  /// The quadrilateral a0 b0 b1 a1 between an edge's two places, or, where the edge turned across
  /// its own earlier place, the two triangles either side of the crossing.
  void addQuad(const Vec2& a0, const Vec2& b0, const Vec2& a1, const Vec2& b1)
  {
    // Parallel edges can pass segmentsCross by rounding (its four signs from ~1e-17 products) and
    // put the crossing at infinity: only a crossing within the edge counts (found by fuzz_shapes).
    const double t = segmentsCross(a0, b0, a1, b1) ? cross(a1 - a0, b1 - a1) / cross(b0 - a0, b1 - a1) : -1.0;
    if (t >= 0.0 && t <= 1.0)
    {
      const Vec2 x = a0 + (b0 - a0) * t;
      add(a0, x, a1);
      add(b0, x, b1);
      return;
    }
    if (std::abs(cross(b0 - a0, b1 - a0)) + std::abs(cross(b1 - a0, a1 - a0)) >= 1e-14)
    {
      addPolygon({a0, b0, b1, a1});
    }
  }

  /// The union's rims (outer ones counter-clockwise, holes clockwise) in metres.
  std::vector<std::vector<Vec2>> rims() const
  {
    ClipperLib::Clipper clipper;
    clipper.AddPaths(paths_, ClipperLib::ptSubject, true);
    ClipperLib::Paths rims;
    clipper.Execute(ClipperLib::ctUnion, rims, ClipperLib::pftNonZero, ClipperLib::pftNonZero);
    // Pieces that touch along an edge can come out with a hairline gap between them after rounding
    // (a sliver of the robot's tail swinging out, apart from the rest): closed by growing the rims
    // by half a millimetre and shrinking them back (mitred: corners stay where they are).
    for (const double grow : {kCleanDistance, -kCleanDistance})
    {
      ClipperLib::ClipperOffset offset(4.0);
      offset.AddPaths(rims, ClipperLib::jtMiter, ClipperLib::etClosedPolygon);
      offset.Execute(rims, grow);
    }
    return fromClipper(std::move(rims), origin_);
  }

private:
  Vec2 origin_;
  ClipperLib::Paths paths_;
};
}  // namespace

void SweptCorridor::build(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start,
                          const std::vector<Vec2>& footprint_in, const CorridorParameters& parameters)
{
  if (!begin(points, lengths, start, parameters) || !footprintProblem(footprint_in).empty())
  {
    placements_.clear();
    return;  // begin() emptied the last build's output
  }
  std::vector<Vec2> footprint = footprint_in;
  for (const Vec2& v : footprint)
  {
    if (!(std::abs(v.x) < 1e3) || !(std::abs(v.y) < 1e3))
    {
      placements_.clear();  // a robot a kilometre wide is a typing error
      return;
    }
  }
  if (signedArea(footprint) < 0)
  {
    std::reverse(footprint.begin(), footprint.end());
  }
  // The footprint where it starts and where it ends, and what each of its edges sweeps between two
  // neighbouring positions: a point the footprint covers at some moment was inside it at the start,
  // or a leading edge crossed it on the way there. Small steps keep the chords of the corners' arcs short
  // (5 degrees at 2.5 m from the centre of the turn: a sagitta of 0.2 mm).
  Pieces pieces(origin_);
  for (const Placement* at : {&placements_.front(), &placements_.back()})
  {
    std::vector<Vec2> placed;
    for (const Vec2& v : footprint)
    {
      placed.push_back(place(*at, v));
    }
    pieces.addPolygon(placed);
  }
  // Where the footprint only translates (a straight stretch: the same heading, positions on one
  // line), its sweep from the first to the last position of the stretch is the same as through
  // every position between: one step instead of many, and for a convex footprint one piece, the
  // hull of the two places (its sweep under a translation, exactly).
  const bool convex = isConvex(footprint);
  for (std::size_t i = 0; i + 1 < placements_.size();)
  {
    const std::size_t j = translationEnd(placements_, i);
    if (j > i && convex)
    {
      pieces.addPolygon(translationHull(footprint, placements_[i], placements_[j]));
      i = j;
      continue;
    }
    const std::size_t next = std::max(j, i + 1);
    for (std::size_t e = 0; e < footprint.size(); ++e)
    {
      const Vec2& a = footprint[e];
      const Vec2& b = footprint[(e + 1) % footprint.size()];
      const Vec2 a0 = place(placements_[i], a), b0 = place(placements_[i], b);
      const Vec2 a1 = place(placements_[next], a), b1 = place(placements_[next], b);
      // An edge that moves inwards all along (its outward normal against both ends' motion; the
      // motion of a rigid step is linear along the edge) only passes over what was already covered.
      const Vec2 outward{b0.y - a0.y, a0.x - b0.x};
      if (dot(a1 - a0, outward) <= 0.0 && dot(b1 - b0, outward) <= 0.0)
      {
        continue;
      }
      pieces.addQuad(a0, b0, a1, b1);
    }
    i = next;
  }
  finish(pieces.rims(), {sideVertex(footprint, 1, true), sideVertex(footprint, -1, true), sideVertex(footprint, 1, false),
                         sideVertex(footprint, -1, false)},
         parameters);
}

void SweptCorridor::buildRound(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start,
                               double radius, const CorridorParameters& parameters)
{
  if (!begin(points, lengths, start, parameters) || !(radius > 0.0) || !(radius < 1e3))
  {
    placements_.clear();
    return;  // begin() emptied the last build's output
  }
  // A disc turns into itself: its sweep is the path's points grown by the radius (Clipper's offset,
  // round ends, arcs within 0.1 mm).
  ClipperLib::Path centre_line;
  for (const Placement& at : placements_)
  {
    centre_line.push_back(toClipper(at.position));
  }
  ClipperLib::ClipperOffset offset(2.0, 1e-4 * kScale);
  offset.AddPath(centre_line, ClipperLib::jtRound, ClipperLib::etOpenRound);
  ClipperLib::Paths rims;
  offset.Execute(rims, radius * kScale);
  finish(fromClipper(std::move(rims), origin_), {Vec2{0, radius}, Vec2{0, -radius}, Vec2{0, radius}, Vec2{0, -radius}},
         parameters);
}

bool SweptCorridor::begin(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start,
                          const CorridorParameters& parameters)
{
  band_.clear();
  edge_lines_.clear();
  edge_triangles_.clear();
  placements_.clear();
  if (points.size() < 2 || lengths.size() != points.size() || !std::isfinite(start) || !(parameters.length > 0.0) ||
      !(parameters.step > 0.0) || !(parameters.turn_step > 0.0) || !(parameters.heading_chord >= 0.0))
  {
    return false;
  }
  const double from = std::clamp(start, 0.0, lengths.back());
  const double to = std::min(from + parameters.length, lengths.back());
  if (!(to - from > 1e-6))
  {
    return false;  // at the destination: nothing left to sweep
  }
  origin_ = pointAtArcLength(points, lengths, from);
  placements_ = placementsAlong(points, lengths, from, to, origin_, parameters);
  // Clipper's integers hold 4.6e13 m at 10 um; a corridor is never near that: anything beyond
  // 1000 km from its start (or not finite) is refused rather than rounded into nonsense.
  for (const Placement& at : placements_)
  {
    if (!(std::abs(at.position.x) < 1e6) || !(std::abs(at.position.y) < 1e6) || !isFinite(at.forward))
    {
      placements_.clear();
    }
  }
  return placements_.size() >= 2;
}

void SweptCorridor::finish(const std::vector<std::vector<Vec2>>& rims, const std::array<Vec2, 4>& sides,
                           const CorridorParameters& parameters)
{
  // The caps behind the robot and beyond the far end are cut off an outer rim where the footprint's
  // outermost points (sides: start left, start right, end left, end right) are, if they come in that
  // order counter-clockwise; holes (a path that loops) and rims without that order are kept whole.
  const Vec2 start_left = place(placements_.front(), sides[0]) + origin_;
  const Vec2 start_right = place(placements_.front(), sides[1]) + origin_;
  const Vec2 end_left = place(placements_.back(), sides[2]) + origin_;
  const Vec2 end_right = place(placements_.back(), sides[3]) + origin_;
  auto toLine = [&](const std::vector<Vec2>& ring, std::size_t first, std::size_t last) {
    std::vector<Vec2> line;
    for (std::size_t i = first;; i = (i + 1) % ring.size())
    {
      line.push_back(ring[i]);
      if (i == last) break;
    }
    return line;
  };
  // The band: each outer rim with the holes inside it, triangulated so that no point is covered twice.
  for (const std::vector<Vec2>& ring : rims)
  {
    if (ring.size() < 3 || !(signedArea(ring) > 1e-4))
    {
      continue;
    }
    std::vector<std::vector<Vec2>> holes;
    for (const std::vector<Vec2>& hole : rims)
    {
      if (hole.size() >= 3 && signedArea(hole) < -1e-4 && insidePolygon(ring, hole.front()))
      {
        holes.push_back(hole);
      }
    }
    const std::vector<Vec2> triangles = triangulatePolygon(ring, holes);
    band_.insert(band_.end(), triangles.begin(), triangles.end());
  }
  for (const std::vector<Vec2>& ring : rims)
  {
    // Slivers between the chords of the corners' arcs can leave specks unswept: holes under 1 cm^2
    // are not drawn (a path that loops leaves far larger ones).
    if (ring.size() < 3 || std::abs(signedArea(ring)) < 1e-4)
    {
      continue;
    }
    if (signedArea(ring) > 0)
    {
      const std::size_t n = ring.size();
      const std::size_t sr = nearestIndex(ring, start_right), er = nearestIndex(ring, end_right);
      const std::size_t el = nearestIndex(ring, end_left), sl = nearestIndex(ring, start_left);
      auto along = [&](std::size_t i) { return (i + n - sr) % n; };  // steps from start_right, counter-clockwise
      if (along(er) > 0 && along(er) < along(el) && along(el) < along(sl))
      {
        edge_lines_.push_back(toLine(ring, sr, er));
        std::vector<Vec2> left = toLine(ring, el, sl);
        std::reverse(left.begin(), left.end());
        edge_lines_.push_back(std::move(left));
        continue;
      }
    }
    std::vector<Vec2> whole = ring;
    whole.push_back(whole.front());
    edge_lines_.push_back(std::move(whole));
  }
  for (const std::vector<Vec2>& line : edge_lines_)
  {
    thickLine(line, false, parameters.edge_width, edge_triangles_);
  }
}
}  // namespace rviz_projector
