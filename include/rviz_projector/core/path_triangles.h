// The triangles a spaced path is drawn with: every arrow (flat outlines, or shaded solids) and the
// destination disc, in buffers kept from one path to the next (no allocation once they are big
// enough). What ProjectedPath hands to its two meshes, and what the benchmarks measure.
#pragma once

#include <cstddef>
#include <vector>

#include "rviz_projector/core/mesh_vertex.h"
#include "rviz_projector/core/spaced_path.h"
#include "rviz_projector/core/spacing_parameters.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
class PathTriangles
{
public:
  enum class ArrowStyle
  {
    Flat,   ///< ArrowOutline: what a projector shows
    Solid,  ///< ArrowSolid: shaded 3D arrows for rviz's main view
  };

  /// Solid arrows are 240 vertices each (a flat one is 9): at most this many are built, the ones
  /// nearest the destination, so a long path or a tiny spacing cannot make a gigabyte mesh.
  static constexpr std::size_t kMaxSolidArrows = 10000;

  /// Rebuilds the triangles for `path` with the arrow and circle sizes of `parameters`; only the
  /// arrow buffer of `style` is filled, the other one is emptied.
  void build(const SpacedPath& path, const SpacingParameters& parameters, ArrowStyle style);

  /// Arrows of the last build that have triangles (invalid, degenerate arrows have none).
  std::size_t arrowsDrawn() const;
  /// Arrows of the last build not drawn because of kMaxSolidArrows (0 for Flat).
  std::size_t arrowsLeftOut() const { return arrows_left_out_; }

  /// Flat arrow triangles (ArrowOutline::kVerticesPerArrow vertices per arrow), style Flat.
  const std::vector<Vec2>& flatArrows() const { return flat_arrows_; }
  /// Shaded arrow triangles (ArrowSolid::kVerticesPerArrow vertices per arrow), style Solid.
  const std::vector<MeshVertex>& solidArrows() const { return solid_arrows_; }
  /// The destination disc; empty when the path has no destination.
  const std::vector<Vec2>& destination() const { return destination_; }

private:
  std::vector<Vec2> flat_arrows_;
  std::vector<MeshVertex> solid_arrows_;
  std::vector<Vec2> destination_;
  std::size_t arrows_left_out_ = 0;
};
}  // namespace rviz_projector
