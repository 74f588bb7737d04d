// libFuzzer target: the projection mask's geometry (core/projection_mask): a LaserScan's returns on
// the floor, dense points thinned to cells, the occluder columns. Invariants: no crash or UB; every
// return is either used or ignored, one floor point per used return, finite for sane inputs;
// snapToCells gives sorted unique cell centres, at most max_cells, and (when complete) every input
// point lies in the cell of one of them; one column of 30 finite vertices per finite point, none
// when Height or Margin is not positive.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_input.h"
#include "rviz_projector/core/occluder_union.h"
#include "rviz_projector/core/projection_mask.h"

using namespace rviz_projector;
using rviz_projector_fuzz::Input;
using rviz_projector_fuzz::sane;

namespace
{
void checkScan(Input& in, std::vector<Vec2>& points)
{
  const std::size_t count = in.integer<std::size_t>(0, 512);
  std::vector<float> ranges(count);
  for (float& r : ranges)
  {
    r = static_cast<float>(in.number(20.0));
  }
  ScanView scan;
  scan.angle_min = in.number(4.0);
  scan.angle_increment = in.number(0.1);
  scan.range_min = in.size(1.0);
  scan.range_max = in.size(30.0);
  scan.ranges = ranges.data();
  scan.count = ranges.size();
  const double qx = in.number(1.0), qy = in.number(1.0), qz = in.number(1.0), qw = in.number(1.0);
  const Vec3 t = in.vec3(10.0);
  const RigidTransform pose = RigidTransform::fromQuaternion(qx, qy, qz, qw, t);
  const MaskInputCount n = scanToFloorPoints(scan, pose, points);
  RP_FUZZ_CHECK(n.used + n.ignored == count);
  RP_FUZZ_CHECK(points.size() == n.used);
  const bool sane_input = sane(scan.angle_min) && sane(scan.angle_increment) && std::fabs(scan.angle_increment) < 1e6 &&
                          sane(qx) && sane(qy) && sane(qz) && sane(qw) && std::fabs(qx) + std::fabs(qy) + std::fabs(qz) +
                          std::fabs(qw) > 1e-3 && std::fabs(qx) + std::fabs(qy) + std::fabs(qz) + std::fabs(qw) < 1e3 &&
                          sane(t) && std::fabs(scan.angle_min) < 1e6;
  if (sane_input)
  {
    for (const Vec2& p : points)
    {
      RP_FUZZ_CHECK(std::isfinite(p.x) && std::isfinite(p.y));
    }
  }
}

void checkCells(Input& in, const std::vector<Vec2>& input)
{
  const double cell = in.size(1.0);
  const std::size_t max_cells = in.integer<std::size_t>(0, 600);
  std::vector<Vec2> cells = input;
  const bool complete = snapToCells(cells, cell, max_cells);
  if (!(std::isfinite(cell) && cell > 0.0))
  {
    RP_FUZZ_CHECK(complete && cells.size() == input.size());  // unchanged
    return;
  }
  RP_FUZZ_CHECK(cells.size() <= max_cells);
  for (std::size_t i = 1; i < cells.size(); ++i)
  {
    const Vec2 &a = cells[i - 1], &b = cells[i];
    RP_FUZZ_CHECK(a.x < b.x || (a.x == b.x && a.y < b.y));  // sorted, unique
  }
  if (!complete || cell < 1e-6)
  {
    return;
  }
  // Every finite, moderately sized point lies within half a cell (+ rounding) of a centre.
  for (const Vec2& p : input)
  {
    if (!(std::fabs(p.x) < 1e6 && std::fabs(p.y) < 1e6))
    {
      continue;
    }
    const double slack = 0.5 * cell * (1.0 + 1e-9) + 1e-9;
    const bool found = std::any_of(cells.begin(), cells.end(), [&](const Vec2& c) {
      return std::fabs(c.x - p.x) <= slack && std::fabs(c.y - p.y) <= slack;
    });
    RP_FUZZ_CHECK(found);
  }
}

void checkColumns(Input& in, const std::vector<Vec2>& points)
{
  const double height = in.size(3.0), margin = in.size(0.5);
  OccluderMesh mesh;
  mesh.build(points, height, margin);
  if (!(std::isfinite(height) && height > 0.0 && std::isfinite(margin) && margin > 0.0))
  {
    RP_FUZZ_CHECK(mesh.triangles().empty());
    return;
  }
  const std::size_t finite = static_cast<std::size_t>(
      std::count_if(points.begin(), points.end(), [](const Vec2& p) { return std::isfinite(p.x) && std::isfinite(p.y); }));
  RP_FUZZ_CHECK(mesh.columns() == finite);
  RP_FUZZ_CHECK(mesh.triangles().size() == finite * OccluderMesh::kVerticesPerColumn);
  if (sane(height) && sane(margin))
  {
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      if (!sane(points[i]))
      {
        return;
      }
    }
    for (const MeshVertex& v : mesh.triangles())
    {
      RP_FUZZ_CHECK(std::isfinite(v.position.x) && std::isfinite(v.position.y) && std::isfinite(v.position.z));
      RP_FUZZ_CHECK(v.position.z >= 0.0 && v.position.z <= height);
    }
  }
}

/// The columns' union (occluder_union.h): formed or refused, never a crash; when formed, its
/// vertices are finite, on the floor or at the height, with unit normals.
void checkUnion(Input& in, const std::vector<Vec2>& points)
{
  const double height = in.size(3.0), margin = in.size(0.5);
  OccluderUnion merged;
  const std::vector<Vec2> none;
  const bool formed = merged.build({{&points, margin}, {&none, margin}}, height);
  if (!formed)
  {
    RP_FUZZ_CHECK(merged.triangles().empty());
    return;
  }
  RP_FUZZ_CHECK(merged.triangles().size() % 3 == 0);
  if (!(std::isfinite(height) && height > 0.0 && std::isfinite(margin) && margin > 0.0))
  {
    RP_FUZZ_CHECK(merged.triangles().empty());
    return;
  }
  for (const MeshVertex& v : merged.triangles())
  {
    RP_FUZZ_CHECK(std::isfinite(v.position.x) && std::isfinite(v.position.y));
    RP_FUZZ_CHECK(v.position.z == 0.0 || v.position.z == height);
    RP_FUZZ_CHECK(std::fabs(std::hypot(v.normal.x, v.normal.y, v.normal.z) - 1.0) < 1e-9);
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Input in(data, size);
  std::vector<Vec2> points;
  checkScan(in, points);
  // Free-form points too (a cloud's floor positions), appended to the scan's.
  const std::size_t extra = in.integer<std::size_t>(0, 256);
  for (std::size_t i = 0; i < extra && !in.empty(); ++i)
  {
    points.push_back(in.vec2(5.0));
  }
  checkCells(in, points);
  checkColumns(in, points);
  checkUnion(in, points);
  return 0;
}
