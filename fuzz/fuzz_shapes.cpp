// libFuzzer target: the floor shapes a display turns into triangles: ArrowOutline, ArrowSolid,
// DiscOutline, FloorGrid, SweptCorridor and OffViewCue, with positions and sizes from the fuzz input.
// Invariants: no crash or UB, the documented vertex counts, finite vertices (and unit normals) for
// sane finite inputs, an arrow contains its tip, a disc its centre, a grid stays within kMaxLines
// lines, a refused corridor footprint draws nothing, and an off-view cue has a reason, draws
// nothing when None and only inside the lit polygon otherwise. Outlines are closed and simple: the
// arrow's outline is counter-clockwise, its triangles use only its corners and cover exactly its
// area, and no two non-adjacent edges meet; the disc's rim closes on itself and its chords do not
// cross (a plain O(n^2) check of every pair of edges).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_input.h"
#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/arrow_solid.h"
#include "rviz_projector/core/disc_outline.h"
#include "rviz_projector/core/floor_grid.h"
#include "rviz_projector/core/off_view_cue.h"
#include "rviz_projector/core/path_location.h"
#include "rviz_projector/core/swept_corridor.h"

using namespace rviz_projector;
using rviz_projector_fuzz::Input;
using rviz_projector_fuzz::sane;

namespace
{
/// Sizes as the displays pass them: PathSpacer::setParameters makes them finite and >= 0.
bool saneSize(double v) { return sane(v) && v >= 0.0; }

double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

/// True when p and q lie on opposite sides of the line through a and b, each further than `margin`.
bool straddles(const Vec2& a, const Vec2& b, const Vec2& p, const Vec2& q, double margin)
{
  const double length = distance(a, b);
  if (!(length > 0.0))
  {
    return false;
  }
  const double dp = cross(b - a, p - a) / length, dq = cross(b - a, q - a) / length;
  return (dp > margin && dq < -margin) || (dp < -margin && dq > margin);
}

/// Segments ab and cd cross, each end further than `margin` from the other segment's line
/// (nearly touching segments, where rounding decides, do not count).
bool cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, double margin)
{
  return straddles(a, b, c, d, margin) && straddles(c, d, a, b, margin);
}

/**
 * True when the closed polygon (last vertex joined to the first) is simple: after merging
 * consecutive vertices closer than `merge`, no two edges that do not share a vertex cross (by more
 * than `touch`: touch < merge, so rounding at a merged vertex is never taken for a crossing).
 */
bool simplePolygon(const std::vector<Vec2>& polygon, double merge, double touch)
{
  std::vector<Vec2> v;
  for (const Vec2& p : polygon)
  {
    if (v.empty() || distance(v.back(), p) > merge)
    {
      v.push_back(p);
    }
  }
  while (v.size() > 1 && distance(v.back(), v.front()) <= merge)
  {
    v.pop_back();
  }
  const std::size_t n = v.size();
  if (n < 3)
  {
    return false;  // collapsed: no area
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t j = i + 2; j < n; ++j)
    {
      if (i == 0 && j == n - 1)
      {
        continue;  // the closing edge is adjacent to the first
      }
      if (cross(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n], touch))
      {
        return false;
      }
    }
  }
  return true;
}

/// Shoelace formula, relative to the first vertex (no cancellation from large coordinates).
double signedArea(const std::vector<Vec2>& polygon)
{
  double twice = 0.0;
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i)
  {
    twice += cross(polygon[i] - polygon[0], polygon[i + 1] - polygon[0]);
  }
  return 0.5 * twice;
}

void arrows(Input& in)
{
  Arrow arrow{in.vec2(5.0), in.vec2(5.0)};
  if (in.boolean())
  {
    arrow.tip = arrow.tail + in.vec2(0.5);  // short arrows, sometimes zero-length
  }
  ArrowDimensions d;
  d.shaft_length = in.size(0.3);
  d.shaft_diameter = in.size(0.3);
  d.head_length = in.size(0.3);
  d.head_diameter = in.size(0.3);
  const bool finite_arrow = isFinite(arrow.tip - arrow.tail) && std::isfinite(norm(arrow.tip - arrow.tail)) &&
                            norm(arrow.tip - arrow.tail) > 0.0;
  const bool all_sane = sane(arrow.tip) && sane(arrow.tail) && saneSize(d.shaft_diameter) &&
                        saneSize(d.head_length) && saneSize(d.head_diameter) && saneSize(d.shaft_length);

  const ArrowOutline outline(arrow, d);
  RP_FUZZ_CHECK(outline.valid() == finite_arrow);
  std::vector<Vec2> flat;
  outline.appendTriangles(flat);
  RP_FUZZ_CHECK(flat.size() == (outline.valid() ? ArrowOutline::kVerticesPerArrow : 0u));
  const Vec2 probe = in.vec2(5.0);
  const double distance_to_probe = outline.distanceTo(probe);
  RP_FUZZ_CHECK(!(distance_to_probe < 0.0));
  if (!outline.valid())
  {
    RP_FUZZ_CHECK(!outline.contains(probe));
  }
  if (outline.valid() && all_sane)
  {
    for (const Vec2& v : flat)
    {
      RP_FUZZ_CHECK(isFinite(v));
    }
    if (sane(probe))
    {
      RP_FUZZ_CHECK(std::isfinite(distance_to_probe));
      // "0 inside" (a point on a zero-width shaft can be at distance 0 without being inside).
      RP_FUZZ_CHECK(!outline.contains(probe) || distance_to_probe == 0.0);
    }
    // The tip is a corner of the head triangle (boundary included), for everyday magnitudes
    // where the 1e-12 edge tolerance is meaningful.
    const double magnitude = std::max({std::fabs(arrow.tip.x), std::fabs(arrow.tip.y), std::fabs(arrow.tail.x),
                                       std::fabs(arrow.tail.y), d.head_diameter, d.head_length});
    if (magnitude < 1e3 && d.head_diameter > 0.0 && norm(arrow.tip - arrow.tail) > 1e-6)
    {
      RP_FUZZ_CHECK(outline.distanceTo(arrow.tip) < 1e-9);
    }
    // Closed and simple, for shapes that are not degenerate at this magnitude (widths and length
    // well above the rounding of the coordinates): counter-clockwise, the triangles use only
    // corners and cover exactly the outline's area, no two non-adjacent edges meet.
    const double scale = std::max(1.0, magnitude + std::max(d.shaft_diameter, d.head_diameter));
    const double length = norm(arrow.tip - arrow.tail);
    if (magnitude < 1e6 && d.shaft_diameter > 1e-6 * scale && d.head_diameter > 1e-6 * scale && length > 1e-6 * scale &&
        d.head_length > 1e-6 * scale)
    {
      const std::vector<Vec2> corners(outline.corners().begin(), outline.corners().end());
      const double area = signedArea(corners);
      RP_FUZZ_CHECK(area > 0.0 && "arrow outline not counter-clockwise");
      double triangles_area = 0.0;
      for (std::size_t t = 0; t + 2 < flat.size(); t += 3)
      {
        triangles_area += signedArea({flat[t], flat[t + 1], flat[t + 2]});
      }
      for (const Vec2& v : flat)
      {
        RP_FUZZ_CHECK(std::any_of(corners.begin(), corners.end(), [&](const Vec2& c) { return c.x == v.x && c.y == v.y; }));
      }
      const double perimeter = 2.0 * length + 2.0 * d.head_diameter + d.shaft_diameter;
      RP_FUZZ_CHECK(std::fabs(triangles_area - area) <= 1e-9 * scale * perimeter && "arrow triangles do not fill the outline");
      RP_FUZZ_CHECK(simplePolygon(corners, 1e-9 * scale, 1e-10 * scale) && "arrow outline self-intersects");
    }
  }

  const ArrowSolid solid(arrow, d);
  std::vector<MeshVertex> mesh;
  solid.appendTriangles(mesh);
  RP_FUZZ_CHECK(mesh.size() == (finite_arrow ? ArrowSolid::kVerticesPerArrow : 0u));
  if (finite_arrow && all_sane)
  {
    for (const MeshVertex& v : mesh)
    {
      RP_FUZZ_CHECK(isFinite(v.position));
      RP_FUZZ_CHECK(isFinite(v.normal));
      RP_FUZZ_CHECK(std::fabs(norm(v.normal) - 1.0) < 1e-6);
    }
  }
}

void discs(Input& in)
{
  const Vec2 centre = in.vec2(5.0);
  const double diameter = in.size(1.0);
  const int segments = in.boolean() ? DiscOutline::kDefaultSegments : in.integer<int>(-5, 4096);
  const DiscOutline disc(centre, diameter, segments);
  std::vector<Vec2> triangles;
  disc.appendTriangles(triangles);
  const bool drawn = isFinite(centre) && std::isfinite(diameter) && diameter > 0.0;
  const std::size_t expected = drawn ? 3u * static_cast<std::size_t>(std::max(segments, 3)) : 0u;
  // A positive diameter so small that half of it rounds to zero draws nothing either.
  RP_FUZZ_CHECK(triangles.size() == expected || (triangles.empty() && 0.5 * diameter == 0.0));
  if (drawn && sane(centre) && sane(diameter))
  {
    for (const Vec2& v : triangles)
    {
      RP_FUZZ_CHECK(isFinite(v));
    }
    RP_FUZZ_CHECK(disc.contains(centre));
    // The fan's rim: each triangle (centre, rim k, rim k+1) starts where the previous one ended,
    // the last ends where the first started (closed), and the rim polygon is simple.
    const double radius = 0.5 * diameter;
    const double scale = std::max({1.0, std::fabs(centre.x), std::fabs(centre.y), radius});
    if (!triangles.empty() && radius > 1e-6 * scale && radius < 1e6)
    {
      std::vector<Vec2> rim;
      for (std::size_t t = 0; t < triangles.size(); t += 3)
      {
        RP_FUZZ_CHECK(triangles[t].x == centre.x && triangles[t].y == centre.y);
        if (t > 0)
        {
          RP_FUZZ_CHECK(triangles[t + 1].x == triangles[t - 1].x && triangles[t + 1].y == triangles[t - 1].y);
        }
        RP_FUZZ_CHECK(signedArea({triangles[t], triangles[t + 1], triangles[t + 2]}) > 0.0 && "disc fan not counter-clockwise");
        rim.push_back(triangles[t + 1]);
      }
      RP_FUZZ_CHECK(distance(triangles.back(), triangles[1]) <= 1e-9 * scale && "disc rim not closed");
      const std::size_t n = rim.size();
      // A chord is 2 r sin(pi / n) long: compare with the rounding of the coordinates.
      if (n <= 64 && 2.0 * radius * std::sin(M_PI / static_cast<double>(n)) > 1e-6 * scale)
      {
        RP_FUZZ_CHECK(simplePolygon(rim, 1e-9 * scale, 1e-10 * scale) && "disc rim self-intersects");
      }
    }
  }
}

void grids(Input& in)
{
  const Vec2 a = in.vec2(30.0);
  const Vec2 b = in.boolean() ? a + Vec2{std::fabs(in.number(30.0)), std::fabs(in.number(30.0))} : in.vec2(30.0);
  const double cell = in.boolean() ? 0.1 : in.size(1.0);
  const FloorGrid grid(a, b, cell);
  const int lines = grid.verticalLineCount();
  RP_FUZZ_CHECK(lines >= 0 && lines <= FloorGrid::kMaxLines);
  std::vector<Vec2> triangles;
  grid.appendTriangles(triangles);
  // Each direction at most kMaxLines rectangles, plus the origin cross: 6 vertices each.
  RP_FUZZ_CHECK(triangles.size() <= 6u * (2u * FloorGrid::kMaxLines + 2u));
  RP_FUZZ_CHECK(triangles.size() % 6u == 0u);
  if (sane(a) && sane(b))
  {
    for (const Vec2& v : triangles)
    {
      RP_FUZZ_CHECK(isFinite(v));
    }
  }
}
void corridors(Input& in)
{
  // The path as the display hands it over: finite points (PathSpacer's input rules).
  std::vector<Vec2> points;
  const int poses = in.integer<int>(0, 40);
  for (int i = 0; i < poses; ++i)
  {
    const Vec2 p = points.empty() || in.boolean() ? in.vec2(20.0) : points.back() + in.vec2(0.3);
    if (isFinite(p))
    {
      points.push_back(p);
    }
  }
  std::vector<double> lengths;
  accumulateArcLengths(points, lengths);
  std::vector<Vec2> footprint;
  const int corners = in.integer<int>(0, 8);
  for (int i = 0; i < corners; ++i)
  {
    footprint.push_back(in.vec2(1.0));
  }
  CorridorParameters parameters;
  parameters.length = in.number(5.0);
  parameters.edge_width = in.size(0.1);
  const double start = in.number(10.0);
  const double radius = in.number(1.0);
  SweptCorridor corridor;
  const bool round = in.boolean();
  if (round)
  {
    corridor.buildRound(points, lengths, start, radius, parameters);
  }
  else
  {
    corridor.build(points, lengths, start, footprint, parameters);
    if (!footprintProblem(footprint).empty())
    {
      RP_FUZZ_CHECK(corridor.band().empty() && corridor.edges().empty() && "a refused footprint drew something");
    }
  }
  RP_FUZZ_CHECK(corridor.band().size() % 3u == 0u);
  RP_FUZZ_CHECK(corridor.edges().size() % 3u == 0u);
  bool sane_input = sane(start) && sane(parameters.length) && sane(parameters.edge_width) && sane(radius);
  for (const Vec2& p : points) sane_input = sane_input && sane(p);
  if (sane_input)
  {
    for (const Vec2& v : corridor.band()) RP_FUZZ_CHECK(isFinite(v));
    for (const Vec2& v : corridor.edges()) RP_FUZZ_CHECK(isFinite(v));
  }
}
/// Whether p is inside the polygon or within `tolerance` of its boundary (either orientation).
bool insideOrNear(const std::vector<Vec2>& polygon, const Vec2& p, double tolerance)
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
    const Vec2 ab = b - a;
    const double l2 = dot(ab, ab);
    const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, dot(p - a, ab) / l2)) : 0.0;
    if (distance(p, a + ab * t) <= tolerance)
    {
      return true;
    }
  }
  return in;
}

void offViewCues(Input& in)
{
  std::vector<Vec2> points;
  const int poses = in.integer<int>(0, 30);
  for (int i = 0; i < poses; ++i)
  {
    points.push_back(points.empty() || in.boolean() ? in.vec2(3.0) : points.back() + in.vec2(0.5));
  }
  std::vector<double> lengths;
  accumulateArcLengths(points, lengths);
  OffViewInput input;
  const int corners = in.integer<int>(0, 12);
  for (int i = 0; i < corners; ++i)
  {
    input.lit.push_back(in.vec2(2.0));
  }
  input.robot = in.vec2(2.0);
  input.heading = in.number(4.0);
  input.start = in.number(5.0);
  input.drawn_from = in.number(5.0);
  OffViewParameters parameters;
  parameters.look_ahead = in.size(3.0);
  parameters.margin = in.size(0.3);
  parameters.arrow_length = in.size(0.5);
  parameters.arrow_width = in.size(0.3);
  parameters.show_below = in.number(1.0);
  parameters.hide_above = in.number(1.0);
  parameters.path_clearance = in.size(0.3);
  parameters.final_approach = in.size(2.0);
  OffViewCue cue;
  for (int call = 0; call < 2; ++call)  // twice: the hysteresis state must not break anything
  {
    const OffViewResult& r = cue.build(points, lengths, input, parameters);
    RP_FUZZ_CHECK(r.triangles.size() % 3u == 0u);
    RP_FUZZ_CHECK(!r.reason.empty());
    RP_FUZZ_CHECK((r.kind != OffViewKind::None || r.triangles.empty()) && "None drew something");
    RP_FUZZ_CHECK((r.kind == OffViewKind::None) == !cue.shown());
    if (r.kind != OffViewKind::None)
    {
      RP_FUZZ_CHECK(r.visible_fraction >= 0.0 && r.visible_fraction <= 1.0 + 1e-9);
      for (const Vec2& v : r.triangles)
      {
        RP_FUZZ_CHECK(isFinite(v));
        RP_FUZZ_CHECK(insideOrNear(input.lit, v, 1e-6) && "a cue vertex outside the lit area");
      }
    }
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Input in(data, size);
  while (!in.empty())
  {
    switch (in.integer<int>(0, 4))
    {
      case 0: arrows(in); break;
      case 1: discs(in); break;
      case 2: corridors(in); break;
      case 3: offViewCues(in); break;
      default: grids(in); break;
    }
  }
  return 0;
}
