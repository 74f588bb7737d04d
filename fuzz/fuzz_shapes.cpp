// libFuzzer target: the floor shapes a display turns into triangles: ArrowOutline, ArrowSolid,
// DiscOutline and FloorGrid, with positions and sizes from the fuzz input. Invariants: no crash or
// UB, the documented vertex counts, finite vertices (and unit normals) for sane finite inputs,
// an arrow contains its tip, a disc its centre, and a grid stays within kMaxLines lines.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_input.h"
#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/arrow_solid.h"
#include "rviz_projector/core/disc_outline.h"
#include "rviz_projector/core/floor_grid.h"

using namespace rviz_projector;
using rviz_projector_fuzz::Input;
using rviz_projector_fuzz::sane;

namespace
{
/// Sizes as the displays pass them: PathSpacer::setParameters makes them finite and >= 0.
bool saneSize(double v) { return sane(v) && v >= 0.0; }

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
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Input in(data, size);
  while (!in.empty())
  {
    switch (in.integer<int>(0, 2))
    {
      case 0: arrows(in); break;
      case 1: discs(in); break;
      default: grids(in); break;
    }
  }
  return 0;
}
