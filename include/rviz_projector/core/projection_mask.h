// The projection mask (issue 15): black occluders over everything a scanner sees above the floor,
// so that no light falls on legs, bags or people, and arrows behind a person (from the projector's
// point of view) are cut where the person blocks the beam. Plain geometry (no ROS, no OGRE).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "rviz_projector/core/mesh_vertex.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// A planar scan as sensor_msgs/LaserScan describes it (ranges in the scanner's x-y plane).
struct ScanView
{
  double angle_min = 0.0;
  double angle_increment = 0.0;
  double range_min = 0.0;
  double range_max = 0.0;
  const float* ranges = nullptr;
  std::size_t count = 0;
};

/// How many returns a conversion used and ignored (NaN/Inf, below range_min, above range_max).
struct MaskInputCount
{
  std::size_t used = 0;
  std::size_t ignored = 0;
};

/**
 * The floor positions (x, y in the fixed frame) of a scan's valid returns: beam i at angle
 * angle_min + i * angle_increment in the scanner's frame, at its range, moved to the fixed frame by
 * `scanner_to_fixed`. A return is valid when its range is finite and within [range_min, range_max]
 * (LaserScan: values outside mean "no return"). `points` is cleared first and keeps its capacity.
 * A non-finite angle or pose: nothing used, everything ignored.
 */
MaskInputCount scanToFloorPoints(const ScanView& scan, const RigidTransform& scanner_to_fixed,
                                 std::vector<Vec2>& points);

/**
 * Appends the floor positions of cloud points (already in the fixed frame) that stand above the
 * floor and below the mask's height: `floor_clearance` < z <= `height` (points on the floor are the
 * floor itself, points above the height are above what the mask covers). Non-finite points are ignored.
 */
MaskInputCount cloudToFloorPoints(const std::vector<Vec3>& cloud, double floor_clearance, double height,
                                  std::vector<Vec2>& points);

/**
 * Thins dense floor points (a depth camera's cloud: 300,000 points a frame) to one point per
 * occupied cell of a square grid of side `cell` (aligned with the fixed frame's axes, cells
 * [k * cell, (k + 1) * cell)), placed at the cell's centre; the result is sorted and unique. A
 * column of half-width `margin + cell / 2` around a cell centre contains the half-width `margin`
 * column of every point of that cell, so masking the centres with the wider margin hides at least
 * what masking every point would (and at most cell / 2 more on each side). Non-finite points are
 * dropped, and so are points more than 2e9 cells from the origin; a cell <= 0 or non-finite leaves
 * `points` unchanged. At most `max_cells` cells are kept
 * (those of the first points in the input order); returns false when some were left out.
 */
bool snapToCells(std::vector<Vec2>& points, double cell, std::size_t max_cells);

/**
 * The occluders: for each floor point a square column from the floor (z = 0 of the fixed frame)
 * to `height`, axis-aligned in the fixed frame, of half-width `margin` (so it contains every point
 * within `margin` of the return, and up to margin * sqrt(2) along the diagonals): four sides and a
 * top, 10 triangles (30 MeshVertex with outward normals) per point, counter-clockwise from outside.
 * Buffers are kept between calls (no allocation once big enough). Non-finite points are skipped;
 * margin <= 0 or height <= 0 (or NaN) draws nothing.
 */
class OccluderMesh
{
public:
  static constexpr std::size_t kVerticesPerColumn = 30;
  /// Clears the mesh, then append(points, height, margin).
  void build(const std::vector<Vec2>& points, double height, double margin);
  /// Adds the columns of `points` (of this height and half-width) to the mesh.
  void append(const std::vector<Vec2>& points, double height, double margin);
  void clear() { triangles_.clear(); }
  const std::vector<MeshVertex>& triangles() const { return triangles_; }
  std::size_t columns() const { return triangles_.size() / kVerticesPerColumn; }

private:
  std::vector<MeshVertex> triangles_;
};

/**
 * Clips everything on one side of a plane out of a perspective projection by making that plane the
 * near clipping plane (Lengyel's oblique view frustum). `projection` is row-major 4x4 (clip = P v,
 * OpenGL conventions, camera looking down -z); `plane` (a, b, c, d) is in the camera's coordinates:
 * points with a x + b y + c z + d >= 0 stay visible. The camera itself must lie on the clipped side
 * (d < 0): otherwise the plane cannot be a near plane and false is returned with `projection`
 * unchanged. x and y of clip space (where pixels land) are unchanged; only depth changes.
 */
bool applyObliqueNearPlane(std::array<double, 16>& projection, const std::array<double, 4>& plane);
}  // namespace rviz_projector
