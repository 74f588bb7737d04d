// Flat arrow shape on the floor: a shaft rectangle and a head triangle (what a projector shows).
#pragma once

#include <array>
#include <vector>

#include "rviz_projector/core/arrow.h"
#include "rviz_projector/core/arrow_dimensions.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/**
 * The head keeps `head_length` (shortened to the arrow's length when the arrow is shorter); the
 * shaft fills the rest of tail -> tip. Shaft length in ArrowDimensions is not used here: in Exact
 * mode it already decided where the tail is, in Paper mode the kept points decide.
 */
class ArrowOutline
{
public:
  /// Vertices appended per arrow by appendTriangles (three triangles).
  static constexpr std::size_t kVerticesPerArrow = 9;

  ArrowOutline(const Arrow& arrow, const ArrowDimensions& dimensions);

  /// The triangles of all `arrows` (what one mesh draws): `out` is cleared, then filled.
  static void trianglesOf(const std::vector<Arrow>& arrows, const ArrowDimensions& dimensions, std::vector<Vec2>& out);

  /// False for a zero-length or non-finite arrow, which has no shape.
  bool valid() const { return valid_; }
  /// Outline, counter-clockwise seen from above: tail right, shaft end right, head right, tip,
  /// head left, shaft end left, tail left.
  const std::array<Vec2, 7>& corners() const { return corners_; }
  /// Appends the two shaft triangles and the head triangle (counter-clockwise from above).
  void appendTriangles(std::vector<Vec2>& out) const;
  /// Whether a floor point lies inside the arrow (boundary included).
  bool contains(const Vec2& p) const;
  /// Distance from a floor point to the arrow's shape (0 inside); infinite for an invalid arrow.
  double distanceTo(const Vec2& p) const;

private:
  bool valid_ = false;
  std::array<Vec2, 7> corners_{};
};
}  // namespace rviz_projector
