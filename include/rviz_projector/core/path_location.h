// Where things are along a path: arc lengths, the point of the path nearest the robot, the path's
// direction at an arc length. Plain geometry for the cues of ProjectedPath (no ROS, no OGRE).
#pragma once

#include <cstddef>
#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Arc length from the first point to each point: `lengths[0] = 0`, `lengths[i] = lengths[i-1] +
/// distance(points[i-1], points[i])`. `lengths` is resized to points.size() (kept capacity: no
/// allocation once big enough). Points must be finite (PathSpacer's input rules: drop others first).
void accumulateArcLengths(const std::vector<Vec2>& points, std::vector<double>& lengths);

/// A place on a path.
struct PathLocation
{
  bool valid = false;      ///< false for an empty path or a non-finite query point
  double arc_length = 0.0; ///< from the path's first point, metres
  Vec2 point;              ///< the nearest point of the path
  double distance = 0.0;   ///< from the query point to `point`, metres
};

/// The point of the polyline nearest to `p` (over all segments, endpoints included). Ties (equal
/// distance to within 1e-9 m) go to the smallest arc length, so a robot standing where a path
/// crosses itself is placed on the earlier part. A single-point path gives that point at arc
/// length 0. `lengths` comes from accumulateArcLengths(points).
PathLocation locateOnPath(const std::vector<Vec2>& points, const std::vector<double>& lengths, const Vec2& p);

/// The point of the polyline at arc length `s` from its first point, clamped to [0, total length].
/// Empty path: {0, 0}.
Vec2 pointAtArcLength(const std::vector<Vec2>& points, const std::vector<double>& lengths, double s);

/// The path's direction at arc length `s`, smoothed for planner paths that zig-zag on a grid: the
/// heading (radians, atan2 of the chord, in (-pi, pi]) of the chord from pointAtArcLength(s) to
/// pointAtArcLength(s + chord); near the end, of the chord from (end - chord) to the end. NaN when the
/// path is shorter than 1e-9 m.
double headingAt(const std::vector<Vec2>& points, const std::vector<double>& lengths, double s, double chord);
}  // namespace rviz_projector
