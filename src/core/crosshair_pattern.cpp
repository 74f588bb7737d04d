#include "rviz_projector/core/crosshair_pattern.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "rviz_projector/core/pinhole_model.h"

namespace rviz_projector
{
namespace
{
constexpr std::uint32_t kMinImageSize = 16;

/// Centre k of n along an image side of `size` pixels (see crosshairPattern): exact integers.
int centreAlong(std::uint32_t size, int k, int n)
{
  if (n <= 1)
  {
    return static_cast<int>(size / 2);  // (size - 1) / 2 rounded up
  }
  // u + 0.5 = size * ((n - 1) + 8 k) / (10 (n - 1)); rounding u half up is flooring u + 0.5.
  const std::int64_t numerator = static_cast<std::int64_t>(size) * ((n - 1) + 8 * k);
  return static_cast<int>(numerator / (10 * (n - 1)));
}

/// Rectangle of whole pixels [col0, col1) x [row0, row1) as edges at pixel boundaries.
PatternRect pixels(int col0, int row0, int col1, int row1)
{
  return {col0 - 0.5, row0 - 0.5, col1 - 0.5, row1 - 0.5};
}

/// The rectangle cut to the image; false when nothing is left.
bool clipToImage(PatternRect& r, std::uint32_t width, std::uint32_t height)
{
  r.x0 = std::max(r.x0, -0.5);
  r.y0 = std::max(r.y0, -0.5);
  r.x1 = std::min(r.x1, width - 0.5);
  r.y1 = std::min(r.y1, height - 0.5);
  return r.x0 < r.x1 && r.y0 < r.y1;
}

/// Start (first pixel) of a label of `size` pixels placed after `after_end` (first free pixel on
/// the positive side) or, when it would leave [0, limit), before `before_start`; clamped into the image.
int placeLabel(int after_end, int before_start, int size, int limit)
{
  if (after_end + size <= limit)
  {
    return after_end;
  }
  if (before_start - size >= 0)
  {
    return before_start - size;
  }
  return std::max(0, limit - size);
}
}  // namespace

std::string crosshairPatternProblem(std::uint32_t width, std::uint32_t height, int rows, int cols)
{
  const std::string size = std::to_string(width) + " x " + std::to_string(height);
  if (width < kMinImageSize || height < kMinImageSize)
  {
    return "image " + size + " is too small for the crosshair pattern (at least " + std::to_string(kMinImageSize) +
           " x " + std::to_string(kMinImageSize) + " pixels)";
  }
  if (width > PinholeModel::kMaxResolution || height > PinholeModel::kMaxResolution)
  {
    return "image " + size + " is larger than " + std::to_string(PinholeModel::kMaxResolution) + " pixels";
  }
  const int max_rc = CrosshairPatternSize::kMaxRowsCols;
  if (rows < 1 || rows > max_rc || cols < 1 || cols > max_rc)
  {
    return "crosshair rows and columns must be 1.." + std::to_string(max_rc) + " (got " + std::to_string(rows) +
           " x " + std::to_string(cols) + ")";
  }
  return "";
}

std::vector<Crosshair> crosshairPattern(std::uint32_t width, std::uint32_t height, int rows, int cols)
{
  std::vector<Crosshair> pattern;
  if (!crosshairPatternProblem(width, height, rows, cols).empty())
  {
    return pattern;
  }
  pattern.reserve(static_cast<std::size_t>(rows * cols));
  for (int r = 0; r < rows; ++r)
  {
    for (int c = 0; c < cols; ++c)
    {
      Crosshair crosshair;
      crosshair.id = r * cols + c + 1;
      crosshair.pixel = {static_cast<double>(centreAlong(width, c, cols)),
                         static_cast<double>(centreAlong(height, r, rows))};
      pattern.push_back(crosshair);
    }
  }
  return pattern;
}

CrosshairStyle crosshairStyle(std::uint32_t width, std::uint32_t height)
{
  const double side = std::min(width, height);
  CrosshairStyle s;
  s.line_width = std::max(1, static_cast<int>(std::lround(side / 400.0)));
  if (s.line_width % 2 == 0)
  {
    ++s.line_width;
  }
  s.arm_length = std::max(2, static_cast<int>(std::lround(side / 20.0)));
  s.digit_height = std::max(7, static_cast<int>(std::lround(side / 12.0)));
  s.digit_width = std::max(4, static_cast<int>(std::lround(0.55 * s.digit_height)));
  s.segment = std::max(1, static_cast<int>(std::lround(s.digit_height / 9.0)));
  s.digit_gap = std::max(2, s.segment);
  return s;
}

unsigned sevenSegmentMask(int digit)
{
  static constexpr unsigned kMasks[10] = {0x3F, 0x06, 0x5B, 0x4F, 0x66, 0x6D, 0x7D, 0x07, 0x7F, 0x6F};
  return digit >= 0 && digit <= 9 ? kMasks[digit] : 0u;
}

CrosshairDrawing crosshairDrawing(const Crosshair& crosshair, std::uint32_t width, std::uint32_t height)
{
  CrosshairDrawing drawing;
  if (width == 0 || height == 0 || !isFinite(crosshair.pixel))
  {
    return drawing;
  }
  const CrosshairStyle s = crosshairStyle(width, height);
  const int w = static_cast<int>(width);
  const int h = static_cast<int>(height);
  const int u = static_cast<int>(std::lround(std::clamp(crosshair.pixel.x, 0.0, w - 1.0)));
  const int v = static_cast<int>(std::lround(std::clamp(crosshair.pixel.y, 0.0, h - 1.0)));
  const int half = (s.line_width - 1) / 2;
  // Arms equally long on all four sides, shortened symmetrically where the border is near.
  const int arm = std::max(0, std::min({s.arm_length, u - half, w - 1 - u - half, v - half, h - 1 - v - half}));

  auto add = [&](std::vector<PatternRect>& out, PatternRect r) {
    if (clipToImage(r, width, height))
    {
      out.push_back(r);
    }
  };
  // Horizontal bar across the centre, then the vertical arms above and below it (no overlap).
  add(drawing.cross, pixels(u - half - arm, v - half, u + half + arm + 1, v + half + 1));
  if (arm > 0)
  {
    add(drawing.cross, pixels(u - half, v - half - arm, u + half + 1, v - half));
    add(drawing.cross, pixels(u - half, v + half + 1, u + half + 1, v + half + arm + 1));
  }

  const std::string digits = std::to_string(std::max(0, crosshair.id));
  const int n = static_cast<int>(digits.size());
  const int label_w = n * s.digit_width + (n - 1) * s.digit_gap;
  const int label_h = s.digit_height;
  // Lower-right quadrant, clear of both arms (which lie on the centre row and column only).
  const int x0 = placeLabel(u + half + 1 + s.digit_gap, u - half - s.digit_gap, label_w, w);
  const int y0 = placeLabel(v + half + 1 + s.digit_gap, v - half - s.digit_gap, label_h, h);
  const int t = s.segment;
  const int dw = s.digit_width;
  const int dh = s.digit_height;
  const int mid = (dh - t) / 2;
  // Segments a..g as [col0, row0, col1, row1) relative to the digit's top-left pixel.
  const int seg[7][4] = {{0, 0, dw, t},       {dw - t, 0, dw, mid + t}, {dw - t, mid, dw, dh}, {0, dh - t, dw, dh},
                         {0, mid, t, dh},     {0, 0, t, mid + t},       {0, mid, dw, mid + t}};
  for (int i = 0; i < n; ++i)
  {
    const unsigned mask = sevenSegmentMask(digits[static_cast<std::size_t>(i)] - '0');
    const int ox = x0 + i * (dw + s.digit_gap);
    for (int k = 0; k < 7; ++k)
    {
      if (mask & (1u << k))
      {
        add(drawing.label, pixels(ox + seg[k][0], y0 + seg[k][1], ox + seg[k][2], y0 + seg[k][3]));
      }
    }
  }
  return drawing;
}

std::vector<PatternRect> crosshairPatternRects(const std::vector<Crosshair>& pattern, std::uint32_t width,
                                               std::uint32_t height)
{
  std::vector<PatternRect> rects;
  for (const Crosshair& crosshair : pattern)
  {
    const CrosshairDrawing d = crosshairDrawing(crosshair, width, height);
    rects.insert(rects.end(), d.cross.begin(), d.cross.end());
    rects.insert(rects.end(), d.label.begin(), d.label.end());
  }
  return rects;
}
}  // namespace rviz_projector
