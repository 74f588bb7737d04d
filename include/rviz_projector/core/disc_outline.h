// A filled disc on the floor (the destination circle) as a triangle fan.
#pragma once

#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
class DiscOutline
{
public:
  /// Segments used for a disc: smooth at projector resolution, cheap to draw.
  static constexpr int kDefaultSegments = 48;

  DiscOutline(const Vec2& centre, double diameter, int segments = kDefaultSegments);

  /// Appends `segments` triangles (counter-clockwise from above); nothing for a zero diameter.
  void appendTriangles(std::vector<Vec2>& out) const;
  bool contains(const Vec2& p) const;

private:
  Vec2 centre_;
  double radius_;
  int segments_;
};
}  // namespace rviz_projector
