// Horizon cue of ProjectedPath: only the next metres of path from the robot are drawn, the last
// metre fading out, so the floor shows what is imminent (no ROS, no OGRE).
#pragma once

namespace rviz_projector
{
/**
 * The visible stretch of a path, in arc length from the path's first point.
 *
 * Drawn: from the robot (`start`, the arc length of the path point nearest the robot) to `end` =
 * start + horizon length. Opacity factor by arc length s:
 *   s < start                      -> 0 (behind the robot: already driven)
 *   start <= s <= end - fade       -> 1
 *   end - fade < s < end           -> (end - s) / fade   (linear)
 *   s >= end                       -> 0
 * with fade = min(fade length, horizon length). A disabled window (the default) gives 1 everywhere.
 * An arrow is judged by its tip (the point farthest along the path): hidden when alpha(tip) is 0,
 * drawn with alpha(tip) otherwise; the destination circle by the path's end.
 */
struct HorizonWindow
{
  bool enabled = false;
  double start = 0.0;
  double end = 0.0;
  double fade = 0.0;

  /// Opacity factor in [0, 1] for a point at arc length s (see above). NaN s: 0.
  double alpha(double s) const;
};

/// The window for a robot at arc length `robot_arc_length` (clamped to >= 0), a horizon of
/// `horizon_length` metres and a fade of `fade_length` metres. Negative or NaN lengths count as 0
/// (a 0 m horizon draws nothing).
HorizonWindow makeHorizon(double robot_arc_length, double horizon_length, double fade_length);
}  // namespace rviz_projector
