// 3D arrow resting on the floor: a shaft cylinder and a head cone (the "3D" style).
#pragma once

#include <vector>

#include "rviz_projector/core/arrow.h"
#include "rviz_projector/core/arrow_dimensions.h"
#include "rviz_projector/core/mesh_vertex.h"

namespace rviz_projector
{
/**
 * Same proportions as ArrowOutline (head keeps head_length, shaft fills the rest), with the axis
 * at half the head diameter above z = 0 so the arrow rests on the floor.
 */
class ArrowSolid
{
public:
  static constexpr int kSides = 16;
  /// Vertices appended per arrow: shaft side, tail cap, cone side, cone base.
  static constexpr std::size_t kVerticesPerArrow = 15 * kSides;

  ArrowSolid(const Arrow& arrow, const ArrowDimensions& dimensions);

  /// The triangles of the first `limit` of `arrows` (what one mesh draws): `out` is cleared, then
  /// filled.
  static void trianglesOf(const std::vector<Arrow>& arrows, const ArrowDimensions& dimensions,
                          std::vector<MeshVertex>& out, std::size_t limit = static_cast<std::size_t>(-1));

  /// Appends kVerticesPerArrow vertices (triangles, counter-clockwise from outside); nothing for
  /// a zero-length arrow.
  void appendTriangles(std::vector<MeshVertex>& out) const;

private:
  bool valid_ = false;
  Vec3 tail_, neck_, tip_;
  Vec3 forward_, side_, up_;
  double shaft_radius_ = 0.0;
  double head_radius_ = 0.0;
  double head_length_ = 0.0;
};
}  // namespace rviz_projector
