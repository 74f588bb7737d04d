#include "rviz_projector/core/letterbox.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
bool PixelRect::operator==(const PixelRect& other) const
{
  return left == other.left && top == other.top && width == other.width && height == other.height;
}

PixelRect letterbox(std::uint32_t image_w, std::uint32_t image_h, int window_w, int window_h)
{
  PixelRect rect;
  if (window_w <= 0 || window_h <= 0)
  {
    return rect;
  }
  if (image_w == 0 || image_h == 0)
  {
    rect.width = window_w;
    rect.height = window_h;
    return rect;
  }
  // Compared as 64-bit: image sizes above INT_MAX must not wrap.
  const std::int64_t iw = image_w;
  const std::int64_t ih = image_h;
  if (iw <= window_w && ih <= window_h && (iw == window_w || ih == window_h))
  {
    // Exact fit along one axis: no scaling at all (1:1 pixels), bars along the other axis.
    rect.width = static_cast<int>(iw);
    rect.height = static_cast<int>(ih);
  }
  else
  {
    const double scale = std::min(double(window_w) / double(iw), double(window_h) / double(ih));
    // Scaled sizes never exceed the window by more than rounding: clamp to it all the same.
    rect.width = static_cast<int>(std::clamp<double>(std::round(double(iw) * scale), 1.0, window_w));
    rect.height = static_cast<int>(std::clamp<double>(std::round(double(ih) * scale), 1.0, window_h));
  }
  rect.left = (window_w - rect.width) / 2;
  rect.top = (window_h - rect.height) / 2;
  return rect;
}

namespace
{
/// Fraction f such that int(float(f) * float(size)) == pixels, for 0 <= pixels <= size.
float fraction(int pixels, int size)
{
  if (pixels <= 0)
  {
    return 0.0f;
  }
  if (pixels >= size)
  {
    return 1.0f;  // 1.0f * size is exact
  }
  // Half a pixel of margin on either side of the truncation point: float rounding (a relative
  // 2^-24 on the fraction and on the product) moves the product by far less than that for any
  // window OGRE can open.
  return static_cast<float>((pixels + 0.5) / size);
}
}  // namespace

std::array<float, 4> viewportFractions(const PixelRect& rect, int window_w, int window_h)
{
  if (window_w <= 0 || window_h <= 0)
  {
    return {0.0f, 0.0f, 0.0f, 0.0f};
  }
  const int left = std::clamp(rect.left, 0, window_w);
  const int top = std::clamp(rect.top, 0, window_h);
  const int width = std::clamp(rect.width, 0, window_w - left);
  const int height = std::clamp(rect.height, 0, window_h - top);
  return {fraction(left, window_w), fraction(top, window_h), fraction(width, window_w), fraction(height, window_h)};
}
}  // namespace rviz_projector
