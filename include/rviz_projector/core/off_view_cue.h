// Off-view cue of ProjectedPath (issue 25, part 3): a projector on the robot lights a patch ahead
// of it, so on the last metre to a goal and while the robot turns in place the floor shows nothing
// of its path. When the path's next metres leave the lit area, a cue is drawn inside it: an arrow at
// the lit edge pointing where the path goes, a turn-in-place glyph, or on the final approach an
// arrow at the destination with its distance. Plain geometry (no ROS, no OGRE).
#pragma once

#include <string>
#include <vector>

#include "rviz_projector/core/digit_text.h"
#include "rviz_projector/core/turn_signal.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
enum class OffViewKind
{
  None,         ///< no cue: the path is visible enough, or the input is unusable (see reason)
  EdgeArrow,    ///< an arrow at the lit area's edge, where the path leaves it
  TurnInPlace,  ///< the curved-arrow glyph: the robot turns before it drives
  Destination,  ///< final approach: an arrow pointing at the destination, its distance beside it
};

/// Name of a kind for statuses ("none", "edge arrow", "turn in place", "destination").
const char* toString(OffViewKind kind);

struct OffViewParameters
{
  /// Metres of path ahead of the robot that are judged (and that the cue stands for).
  double look_ahead = 1.5;
  /// Distance the cue's arrow tip keeps from the lit area's edge, metres.
  double margin = 0.15;
  /// Arrow length (tail to tip) and head width, metres; the shaft is half the head's width.
  double arrow_length = 0.3;
  double arrow_width = 0.12;
  /// Hysteresis on the visible fraction (the part of the next look_ahead metres inside the lit
  /// area, over their length): a cue appears when it drops below `show_below`, and goes once it
  /// reaches `hide_above` (>= show_below), so a path at the threshold does not flicker.
  double show_below = 0.25;
  double hide_above = 0.4;
  /// The robot turns in place when the path's direction at it differs from its heading by more
  /// than this, radians (default 60 degrees).
  double turn_angle = 1.0471975511965976;
  /// Chord over which the path's direction is measured (headingAt), metres.
  double chord = 0.2;
  /// Final approach: the destination is at most this much path ahead of the robot, metres.
  double final_approach = 1.0;
  /// Turn-in-place glyph size (appendTurnGlyph), metres across.
  double glyph_size = 0.3;
  /// Height of the distance label's digits, metres.
  double digit_height = 0.1;
  /// Half the width of the band along the path that the cue keeps clear (the visible arrows:
  /// half their head width plus a gap), metres.
  double path_clearance = 0.1;
};

struct OffViewInput
{
  /// The lit area on the floor: a simple polygon with area, either orientation (FloorFootprint's
  /// outline() is clockwise).
  std::vector<Vec2> lit;
  /// The robot's floor position (in the path's frame; only checked to be finite: the cue works from
  /// `start`) and heading (radians: the turn-in-place test and the label's reading direction).
  Vec2 robot;
  double heading = 0.0;
  /// The robot's place on the path, arc length from its first point (locateOnPath(robot), as the
  /// horizon uses it); clamped to the path.
  double start = 0.0;
  /// Arc length from which the display draws the path's arrows: the horizon's start when the horizon
  /// is on, else 0 (the whole path is drawn). The cue keeps clear of the path from there on; NaN: 0.
  double drawn_from = 0.0;
};

struct OffViewResult
{
  OffViewKind kind = OffViewKind::None;
  /// Triangles to draw (3 vertices each, counter-clockwise from above); empty for None, and when
  /// a cue is wanted but no place inside the lit area keeps clear of the visible path.
  std::vector<Vec2> triangles;
  /// Why (None) or what (a cue), for a status.
  std::string reason;
  /// None because nothing needs showing (the path or the destination is visible, or the robot has
  /// arrived): the design working, not a fault. False for every refusal of unusable input.
  bool by_design = false;
  /// The arrow's tip (EdgeArrow, Destination) or the glyph's centre (TurnInPlace).
  Vec2 anchor;
  /// Unit vector the arrow points along; for TurnInPlace the robot's heading.
  Vec2 direction;
  TurnSide turn = TurnSide::None;  ///< TurnInPlace: which way
  std::string label;               ///< Destination: the distance drawn, e.g. "0.6 m" (empty if no room)
  double visible_fraction = 0.0;   ///< of the next look_ahead metres, inside the lit area
  double scale = 1.0;              ///< 1, or less when the cue was shrunk to fit beside the path
};

/**
 * Decides and draws the off-view cue for one instant. Keeps the hysteresis state between calls
 * (reset by any call that ends in None for unusable input). In order:
 *
 * 1. Unusable input -> None with a reason: fewer than 2 path points or lengths not matching, a
 *    non-finite robot pose or start, a lit polygon with < 3 points, non-finite or huge (> 1e6 m)
 *    coordinates, self-crossing or without area, or too small to keep `margin` from its edge.
 * 2. The window is [start, start + min(look_ahead, path left)]; shorter than 1 cm: None (arrived).
 *    visible_fraction = length of the window's path inside the lit polygon / window length, exact
 *    (the path's crossings with the polygon's edges). None while the path is visible (hysteresis
 *    above).
 * 3. None ("destination visible") when the robot does not turn in place (below), the window reaches
 *    the destination and the destination is inside the lit polygon: its circle shows where the robot
 *    goes. Otherwise, TurnInPlace when |wrap(headingAt(start, chord) - heading)| > turn_angle: appendTurnGlyph
 *    centred on the lit area's centroid (pulled into the area by `margin`), bending to the side of the
 *    difference's sign (> 0: Left; exactly behind counts as Left).
 * 4. Destination when the path left is <= final_approach and its last point is outside the lit
 *    polygon: an arrow whose tip is the point of the lit area shrunk by `margin` nearest the
 *    destination, pointing at it; its label "d.d m" (arc length left) in seven-segment digits beside
 *    the arrow, reading along the robot's left (upright for a person in front of the robot).
 * 5. EdgeArrow otherwise: the target is where the window's path last leaves the lit polygon, or the
 *    window's end when it never is inside; the arrow's tip is the point of the shrunk area nearest
 *    the target, pointing along headingAt(target).
 *
 * Clear of the visible path: a cue never comes within path_clearance of the path that is drawn
 * (arc >= drawn_from). A cue that would is shifted sideways (perpendicular to its direction, in
 * 5 cm steps up to 0.6 m, nearer first, left before right) and then back into the area (10 cm
 * steps up to 0.3 m); then shrunk to 3/4 and 1/2; every vertex must stay inside the lit polygon.
 * If nothing fits, the kind stays but no triangles are drawn and the reason says so.
 */
class OffViewCue
{
public:
  const OffViewResult& build(const std::vector<Vec2>& points, const std::vector<double>& lengths,
                             const OffViewInput& input, const OffViewParameters& parameters);
  const OffViewResult& result() const { return result_; }
  /// Whether the last call showed a cue (the hysteresis state).
  bool shown() const { return shown_; }
  void reset() { shown_ = false; }

private:
  OffViewResult result_;
  bool shown_ = false;
};

}  // namespace rviz_projector
