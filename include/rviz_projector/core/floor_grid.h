// A metric test pattern for the floor: thin lines every cell, bold lines every metre, origin cross.
#pragma once

#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
class FloorGrid
{
public:
  /// Line widths, metres: visible at projector resolution, thin enough to measure against.
  static constexpr double kCellLineWidth = 0.004;
  static constexpr double kMetreLineWidth = 0.012;
  /// Half-length of the origin cross arms, metres.
  static constexpr double kOriginMark = 0.15;
  /// Lines drawn at most per direction (bounds memory for a huge area).
  static constexpr int kMaxLines = 2000;

  /// Grid with `cell` metre cells covering the rectangle [min, max] of the floor.
  FloorGrid(const Vec2& min, const Vec2& max, double cell = 0.1);

  /// Appends the lines and the origin cross as flat triangles.
  void appendTriangles(std::vector<Vec2>& out) const;
  /// Number of grid lines parallel to the y axis (at constant x).
  int verticalLineCount() const;

private:
  Vec2 min_;
  Vec2 max_;
  double cell_;
};
}  // namespace rviz_projector
