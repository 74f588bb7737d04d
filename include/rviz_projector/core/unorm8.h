// The byte an 8-bit normalised channel holds for a colour component c: OpenGL's conversion of a
// float to an unsigned normalised integer, round(255 c) of c clamped to 0..1 (what a clear of an
// RGBA8 target writes). The warp compares the ideal render's texels with its clear colour in these
// bytes, and its eraser paints them back in the same bytes (warp_eraser.h).
#pragma once

#include <cmath>
#include <cstdint>

namespace rviz_projector
{
inline std::uint8_t unorm8(float c)
{
  const float clamped = std::isnan(c) ? 0.0f : (c < 0.0f ? 0.0f : (c > 1.0f ? 1.0f : c));
  return static_cast<std::uint8_t>(std::lround(clamped * 255.0f));
}
}  // namespace rviz_projector
