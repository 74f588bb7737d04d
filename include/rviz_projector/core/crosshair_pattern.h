// The calibration pattern: numbered crosshairs at fixed projector pixels (issue 12).
//
// One function decides where the crosshairs are (crosshairPattern); the ProjectorCamera draws them
// there and `calibrate_projector --pattern` writes the same pixels into the points template.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
struct Crosshair
{
  int id = 0;   ///< 1 .. rows * cols, row by row from the top-left
  Vec2 pixel;   ///< centre, ROS/OpenCV pixel convention (see PinholeModel); always whole pixels
};

/// An axis-aligned rectangle in pixel coordinates, edges at pixel boundaries (x0 < x1, y0 < y1,
/// pixel (u, v) covers [u - 0.5, u + 0.5] x [v - 0.5, v + 0.5]).
struct PixelRect
{
  double x0 = 0.0;
  double y0 = 0.0;
  double x1 = 0.0;
  double y1 = 0.0;
};

struct CrosshairPatternSize
{
  static constexpr int kDefaultRows = 3;
  static constexpr int kDefaultCols = 3;
  static constexpr int kMaxRowsCols = 10;
  /// Fraction of the image's width and height the crosshair centres span.
  static constexpr double kCoverage = 0.8;
};

/**
 * The crosshair centres for an image of width x height pixels: rows x cols centres spread evenly
 * over the central kCoverage of the image (one row or column: the centre line), each rounded to
 * the nearest whole pixel. Empty when the size or rows/cols are out of range
 * (1..kMaxRowsCols, image at least 16 x 16 pixels).
 */
std::vector<Crosshair> crosshairPattern(std::uint32_t width, std::uint32_t height,
                                        int rows = CrosshairPatternSize::kDefaultRows,
                                        int cols = CrosshairPatternSize::kDefaultCols);

/// Why crosshairPattern() would return nothing ("" when it returns the pattern).
std::string crosshairPatternProblem(std::uint32_t width, std::uint32_t height, int rows, int cols);

/**
 * What the display draws, white on black, in pixel coordinates: for every crosshair a cross of
 * odd line width centred exactly on its pixel (arms long enough to tape, a gap-free centre), and
 * its id as seven-segment digits beside it, tall enough to read on the floor. Rectangles only, so
 * any renderer maps them to quads.
 */
std::vector<PixelRect> crosshairPatternRects(const std::vector<Crosshair>& pattern, std::uint32_t width,
                                             std::uint32_t height);
}  // namespace rviz_projector
