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
/// (Not called PixelRect: letterbox.h already has a PixelRect of whole pixels in this namespace, and
/// a translation unit including both headers would not compile.)
struct PatternRect
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
 * (1..kMaxRowsCols, image at least 16 x 16 pixels, at most PinholeModel::kMaxResolution).
 *
 * Exactly: with the image's outer pixel edges at -0.5 and W - 0.5, column i of n (n > 1) lies at
 * u = -0.5 + 0.1 W + i * 0.8 W / (n - 1); one column at u = (W - 1) / 2; the same for rows with H.
 * Ties round up (u = k + 0.5 -> k + 1), computed in integers: u = floor(W ((n - 1) + 8 i) / (10 (n - 1))),
 * so the result does not depend on floating-point rounding. E.g. 1280 x 800, 3 x 3: u = 128, 640,
 * 1152 and v = 80, 400, 720; ids 1, 2, 3 on the top row.
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
std::vector<PatternRect> crosshairPatternRects(const std::vector<Crosshair>& pattern, std::uint32_t width,
                                               std::uint32_t height);

/// Sizes of one crosshair's drawing, pixels (whole numbers), for an image of width x height.
struct CrosshairStyle
{
  int line_width = 1;     ///< odd: max(1, round(min(W, H) / 400) made odd by rounding up)
  int arm_length = 2;     ///< from the centre pixel's edge to the arm's end: round(min(W, H) / 20)
  int digit_height = 7;   ///< max(7, round(min(W, H) / 12))
  int digit_width = 4;    ///< round(0.55 * digit_height)
  int segment = 1;        ///< seven-segment stroke: max(1, round(digit_height / 9))
  int digit_gap = 2;      ///< between digits, and between the cross's arms and the label
};
CrosshairStyle crosshairStyle(std::uint32_t width, std::uint32_t height);

/// One crosshair's drawing: the cross (its rectangles do not overlap; their union is symmetric
/// about the centre pixel; arms shortened symmetrically near the border) and the id's digits
/// (seven-segment, to the lower right of the centre clear of the arms; moved to the left and/or
/// above when they would leave the image). Every rectangle lies inside the image.
struct CrosshairDrawing
{
  std::vector<PatternRect> cross;
  std::vector<PatternRect> label;
};
CrosshairDrawing crosshairDrawing(const Crosshair& crosshair, std::uint32_t width, std::uint32_t height);

/// Seven-segment digits: bit 0 = a (top), 1 = b (top right), 2 = c (bottom right), 3 = d (bottom),
/// 4 = e (bottom left), 5 = f (top left), 6 = g (middle). Digits outside 0..9 give 0.
unsigned sevenSegmentMask(int digit);
}  // namespace rviz_projector
