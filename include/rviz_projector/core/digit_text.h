// Seven-segment text on the floor (the off-view cue's distance label, "0.6 m"): digits as
// triangles a projector can show. Plain geometry (no ROS, no OGRE).
#pragma once

#include <string>
#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Width of `text` drawn by appendDigitTriangles at `height` (metres along the reading direction).
double digitTextWidth(const std::string& text, double height);

/**
 * Seven-segment text as triangles appended to `out` (counter-clockwise from above): '0'-'9', '.',
 * 'm' and ' '; other characters are skipped (no advance). `origin` is the bottom-left corner of the
 * first character, `direction` the reading direction (normalised here), up is its left-hand
 * perpendicular. A digit is 0.5 height wide with strokes height / 8, characters 0.2 height apart;
 * '.' is a stroke-sized square on the baseline; 'm' is half the height tall, a digit wide. Nothing
 * for non-finite input, height <= 0 or a zero direction. Returns the number of characters drawn.
 */
int appendDigitTriangles(const std::string& text, const Vec2& origin, double height, const Vec2& direction,
                         std::vector<Vec2>& out);

/// The same, returning the triangles.
std::vector<Vec2> digitTriangles(const std::string& text, const Vec2& origin, double height, const Vec2& direction);
}  // namespace rviz_projector
