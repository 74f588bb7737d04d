// The projection mask's occluders drawn once (issue 25's CPU budget): the union of the columns'
// floor squares, its walls from the floor to the mask's height and its top. The same solid as
// OccluderMesh's columns, so the same pixels, without their overdraw: a person's scan is ~50
// returns 1 cm apart, each a column 20 cm wide, and every pixel of the person's shadow was shaded
// by ~20 columns (on a software renderer half of projector_host's CPU on the demo scene,
// doc/dev/performance.md). Plain geometry (Clipper, no ROS, no OGRE).
#pragma once

#include <cstddef>
#include <vector>

#include "rviz_projector/core/mesh_vertex.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Floor points, each the centre of an axis-aligned square of half-width `margin` (OccluderMesh's
/// columns).
struct OccluderSquares
{
  const std::vector<Vec2>* points = nullptr;
  double margin = 0.0;
};

class OccluderUnion
{
public:
  /// More squares than this: build() returns false (the union would cost more than it saves). Its
  /// cost grows with the square of the squares along a wall (Clipper's intersections and the top's
  /// ear clipping): 0.09 ms for 50, 0.28 ms for 100, 0.9 ms for 200, 17 ms for 1,000
  /// (MaskUpdate+Union+Mesh, doc/bench/micro-latest.txt). A person is ~50 (up to 170 close to the
  /// scanner, in the demo); a scan of a room's walls is drawn as columns, as before.
  static constexpr std::size_t kMaxSquares = 200;
  /// Farther than this from the first square (metres): build() returns false (Clipper's integers).
  static constexpr double kMaxExtent = 1e6;

  /**
   * Triangles (MeshVertex, counter-clockwise seen from outside, outward normals) of the union of
   * the squares of every set, from z = 0 to `height`: a wall on each edge of the union's outline
   * (outer rings and holes) and its top. Non-finite points are skipped; a set with a margin <= 0
   * (or NaN) and a height <= 0 (or NaN) add nothing. Returns false, with no triangles, when the
   * union is not formed (more than kMaxSquares squares, a square beyond kMaxExtent, or a top the
   * triangulation could not cover exactly): then draw OccluderMesh's columns instead.
   */
  bool build(const std::vector<OccluderSquares>& sets, double height);
  const std::vector<MeshVertex>& triangles() const { return triangles_; }
  /// The squares (columns) of the last build() that formed the union.
  std::size_t squares() const { return squares_; }

private:
  std::vector<MeshVertex> triangles_;
  std::size_t squares_ = 0;
};
}  // namespace rviz_projector
