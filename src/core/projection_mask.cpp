#include "rviz_projector/core/projection_mask.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>
#include <utility>

#include <opencv2/core.hpp>

namespace rviz_projector
{
MaskInputCount scanToFloorPoints(const ScanView& scan, const RigidTransform& scanner_to_fixed,
                                 std::vector<Vec2>& points)
{
  points.clear();
  MaskInputCount count;
  const Vec3 origin = scanner_to_fixed.apply(Vec3{0.0, 0.0, 0.0});
  if (!scan.ranges || !std::isfinite(scan.angle_min) || !std::isfinite(scan.angle_increment) ||
      !std::isfinite(origin.x) || !std::isfinite(origin.y) || !std::isfinite(origin.z))
  {
    count.ignored = scan.count;
    return count;
  }
  for (std::size_t i = 0; i < scan.count; ++i)
  {
    const double range = scan.ranges[i];
    // NaN fails every comparison: ignored with the out-of-range returns.
    if (!(std::isfinite(range) && range >= scan.range_min && range <= scan.range_max))
    {
      ++count.ignored;
      continue;
    }
    const double angle = scan.angle_min + static_cast<double>(i) * scan.angle_increment;
    const Vec3 p = scanner_to_fixed.apply(Vec3{range * std::cos(angle), range * std::sin(angle), 0.0});
    points.push_back(Vec2{p.x, p.y});
    ++count.used;
  }
  return count;
}

MaskInputCount cloudToFloorPoints(const std::vector<Vec3>& cloud, double floor_clearance, double height,
                                  std::vector<Vec2>& points)
{
  MaskInputCount count;
  for (const Vec3& p : cloud)
  {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && p.z > floor_clearance && p.z <= height)
    {
      points.push_back(Vec2{p.x, p.y});
      ++count.used;
    }
    else
    {
      ++count.ignored;
    }
  }
  return count;
}

bool snapToCells(std::vector<Vec2>& points, double cell, std::size_t max_cells)
{
  if (!(std::isfinite(cell) && cell > 0.0))
  {
    return true;
  }
  // Cell indices as integers (exact comparisons); points too far out for a 32-bit index (2e9 cells:
  // 10,000 km at 5 mm) are dropped. One pass in input order with a hash set (a depth camera's
  // neighbouring points share their cell: the last cell is checked first), then the few cells sorted.
  constexpr double kIndexLimit = 2.0e9;
  std::unordered_set<std::uint64_t> seen;
  std::vector<std::pair<std::int32_t, std::int32_t>> cells;
  bool complete = true;
  bool have_last = false;
  std::uint64_t last = 0;
  for (const Vec2& p : points)
  {
    const double kx = std::floor(p.x / cell), ky = std::floor(p.y / cell);
    if (!(std::abs(kx) < kIndexLimit && std::abs(ky) < kIndexLimit))  // also false for NaN/Inf
    {
      continue;
    }
    const auto ix = static_cast<std::int32_t>(kx), iy = static_cast<std::int32_t>(ky);
    const std::uint64_t key = (std::uint64_t(std::uint32_t(ix)) << 32) | std::uint32_t(iy);
    if (have_last && key == last)
    {
      continue;
    }
    have_last = true;
    last = key;
    if (seen.count(key) != 0)
    {
      continue;
    }
    if (cells.size() == max_cells)
    {
      complete = false;  // a new cell beyond the limit: left out
      continue;
    }
    seen.insert(key);
    cells.emplace_back(ix, iy);
  }
  std::sort(cells.begin(), cells.end());
  points.clear();
  for (const auto& c : cells)
  {
    points.push_back(Vec2{(static_cast<double>(c.first) + 0.5) * cell, (static_cast<double>(c.second) + 0.5) * cell});
  }
  return complete;
}

void OccluderMesh::build(const std::vector<Vec2>& points, double height, double margin)
{
  triangles_.clear();
  append(points, height, margin);
}

void OccluderMesh::append(const std::vector<Vec2>& points, double height, double margin)
{
  if (!(std::isfinite(height) && height > 0.0 && std::isfinite(margin) && margin > 0.0))
  {
    return;
  }
  triangles_.reserve(triangles_.size() + points.size() * kVerticesPerColumn);
  const auto quad = [this](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& normal) {
    // a b c d counter-clockwise seen from outside (along -normal).
    triangles_.insert(triangles_.end(), {MeshVertex{a, normal}, MeshVertex{b, normal}, MeshVertex{c, normal},
                                         MeshVertex{a, normal}, MeshVertex{c, normal}, MeshVertex{d, normal}});
  };
  for (const Vec2& p : points)
  {
    if (!isFinite(p))
    {
      continue;
    }
    const double x0 = p.x - margin, x1 = p.x + margin, y0 = p.y - margin, y1 = p.y + margin;
    const double h = height;
    quad(Vec3{x1, y0, 0}, Vec3{x1, y1, 0}, Vec3{x1, y1, h}, Vec3{x1, y0, h}, Vec3{1, 0, 0});    // +x
    quad(Vec3{x1, y1, 0}, Vec3{x0, y1, 0}, Vec3{x0, y1, h}, Vec3{x1, y1, h}, Vec3{0, 1, 0});    // +y
    quad(Vec3{x0, y1, 0}, Vec3{x0, y0, 0}, Vec3{x0, y0, h}, Vec3{x0, y1, h}, Vec3{-1, 0, 0});   // -x
    quad(Vec3{x0, y0, 0}, Vec3{x1, y0, 0}, Vec3{x1, y0, h}, Vec3{x0, y0, h}, Vec3{0, -1, 0});   // -y
    quad(Vec3{x0, y0, h}, Vec3{x1, y0, h}, Vec3{x1, y1, h}, Vec3{x0, y1, h}, Vec3{0, 0, 1});    // top
  }
}

bool applyObliqueNearPlane(std::array<double, 16>& projection, const std::array<double, 4>& plane)
{
  for (double v : plane)
  {
    if (!std::isfinite(v))
    {
      return false;
    }
  }
  if (!(plane[3] < 0.0))
  {
    return false;  // the camera is on the visible side: the plane cannot be the near plane
  }
  const cv::Matx44d m(projection.data());
  bool invertible = true;
  const cv::Matx44d inverse = m.inv(cv::DECOMP_LU, &invertible);
  if (!invertible)
  {
    return false;
  }
  const auto sign = [](double v) { return v > 0.0 ? 1.0 : v < 0.0 ? -1.0 : 0.0; };
  // The clip-space corner opposite the plane (Lengyel): the far corner in the plane's direction.
  const cv::Vec4d q = inverse * cv::Vec4d(sign(plane[0]), sign(plane[1]), 1.0, 1.0);
  const cv::Vec4d c(plane[0], plane[1], plane[2], plane[3]);
  const double along = c.dot(q);
  if (!(std::abs(along) > 1e-300) || !std::isfinite(along))
  {
    return false;
  }
  const cv::Vec4d scaled = c * (2.0 / along);
  for (int j = 0; j < 4; ++j)
  {
    projection[8 + j] = scaled[j] - projection[12 + j];  // third row: the new near (and far) plane
  }
  return true;
}
}  // namespace rviz_projector
