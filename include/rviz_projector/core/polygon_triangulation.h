// Triangles that cover a polygon (with holes) exactly once: what a translucent fill needs, where
// overlapping triangles would blend twice (the swept corridor's band). Ear clipping, holes joined to
// the outer ring by bridges. Plain geometry (no ROS, no OGRE).
#pragma once

#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Counter-clockwise triangles (three vertices each) covering `outer` minus `holes` once. `outer` in
/// either orientation, simple; each hole simple and inside it. A numerically degenerate rest (a
/// sliver too thin to cut) is left out rather than looped on.
std::vector<Vec2> triangulatePolygon(std::vector<Vec2> outer, std::vector<std::vector<Vec2>> holes = {});

/// Whether p is inside the polygon (even-odd; boundary points either way).
bool insidePolygon(const std::vector<Vec2>& polygon, const Vec2& p);

/// The polygon's area, positive when counter-clockwise (the shoelace formula).
double signedArea(const std::vector<Vec2>& polygon);
}  // namespace rviz_projector
