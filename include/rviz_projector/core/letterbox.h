// Where the projector's image goes in its output window: uniform scale, centred, black bars
// (letterbox), as exact integer pixels, and the relative viewport that makes OGRE draw exactly there.
#pragma once

#include <array>
#include <cstdint>

namespace rviz_projector
{
/// A rectangle of whole pixels in a window: left/top from the window's top-left corner.
struct PixelRect
{
  int left = 0;
  int top = 0;
  int width = 0;
  int height = 0;
  bool operator==(const PixelRect& other) const;
  bool operator!=(const PixelRect& other) const { return !(*this == other); }
};

/**
 * Where an image of image_w x image_h pixels is drawn in a window of window_w x window_h: uniform
 * scale, centred, black bars. When the image fits exactly along one axis and is not larger along
 * the other, 1:1 (no scaling). Otherwise scale = min(ww/iw, wh/ih), sizes rounded to nearest,
 * >= 1, left = (ww - width) / 2, top = (wh - height) / 2 (integer division).
 * Zero/negative window -> all zeros; zero image -> whole window.
 */
PixelRect letterbox(std::uint32_t image_w, std::uint32_t image_h, int window_w, int window_h);

/**
 * Relative viewport dimensions (left, top, width, height) for OGRE's Viewport that OGRE turns into
 * exactly `rect` in a window of window_w x window_h.
 *
 * OGRE 1.12 (Viewport::_updateDimensions) computes each actual dimension on its own as
 * int(relative * size), both factors single-precision floats, truncated: left, top, width and
 * height independently (the width is not right edge minus left). The naive fraction pixels / size
 * can land a hair below the integer after float rounding and lose a pixel (e.g. a 1024x768 image
 * in an 854x480 window), so each fraction aims at the middle of its pixel, (pixels + 0.5) / size,
 * where truncation is immune to rounding; 0 and the full size are exact (0 and 1).
 * A rectangle outside the window is clamped to it; a zero or negative window gives all zeros.
 */
std::array<float, 4> viewportFractions(const PixelRect& rect, int window_w, int window_h);
}  // namespace rviz_projector
