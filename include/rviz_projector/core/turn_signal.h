// Turn-signal cue of ProjectedPath: a coming sharp turn of the path, and the curved-arrow glyph
// shown in front of the robot, to the inside of the turn (no ROS, no OGRE).
#pragma once

#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
enum class TurnSide
{
  None,
  Left,   ///< counter-clockwise seen from above (+z)
  Right,  ///< clockwise
};

struct TurnSignalParameters
{
  /// A turn is signalled when the path turns by more than this, radians (default 45 degrees).
  double angle = 0.785398163397448;
  /// ... within this much path ahead of the robot, metres.
  double distance = 1.5;
  /// Chord over which the path's direction is measured (smooths grid zig-zags), metres.
  double chord = 0.2;
  /// Step between direction samples, metres.
  double step = 0.05;
};

struct TurnDetection
{
  TurnSide side = TurnSide::None;
  /// Arc length ahead of the robot (from `start`) where the accumulated turn first exceeded the angle.
  double ahead = 0.0;
  /// The path's heading at the robot (radians): the glyph's reference direction. NaN if unknown.
  double heading = 0.0;
};

/**
 * Walks the path from arc length `start` (the robot's place on it) to start + distance in steps of
 * `step`, sampling headingAt(s, chord) (path_location.h), and sums the heading changes between
 * consecutive samples, each wrapped to (-pi, pi]. The first time |sum| exceeds `angle`, the turn is
 * on the side of the sum's sign (> 0: Left). A straight path gives None; an S-bend whose each bend
 * stays under the angle gives None; a U-turn gives its side. Samples beyond the path's end are not
 * taken. Empty, single-point or non-finite input: None.
 */
TurnDetection detectTurn(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start,
                         const TurnSignalParameters& parameters);

/**
 * The turn-signal glyph as triangles (3 vertices each, counter-clockwise seen from above) appended
 * to `triangles`: a curved arrow (a quarter-circle band ending in an arrow head) that bends to
 * `side`, drawn in front of the robot, to the inside of the turn.
 *
 * Placement: centred at robot + ahead * forward(heading) + aside * left-normal(heading) for Left (the
 * right normal for Right): `ahead` metres in front of the robot and `aside` to the side, where a projector
 * that lights the floor in front of the robot can show it. `size` metres across (its box), the band
 * `size / 5` wide; the band starts pointing along `heading` and turns by 90 degrees to `side`, the
 * head at its end pointing along the turned direction. Nothing is appended for TurnSide::None,
 * size <= 0 or non-finite inputs.
 */
void appendTurnGlyph(const Vec2& robot, double heading, TurnSide side, double ahead, double aside, double size,
                     std::vector<Vec2>& triangles);

/// A cross (an X of two bars, `width` wide, `size` metres from corner to corner along each bar)
/// centred at `centre`, as triangles appended to `triangles`: the destination of a failed goal.
void appendCross(const Vec2& centre, double size, double width, std::vector<Vec2>& triangles);
}  // namespace rviz_projector
