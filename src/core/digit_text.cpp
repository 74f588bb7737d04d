#include "rviz_projector/core/digit_text.h"

#include <cmath>

namespace rviz_projector
{
namespace
{
// Segments of a seven-segment digit, bit i for segment "abcdefg"[i]: a top, b top right, c bottom
// right, d bottom, e bottom left, f top left, g middle.
constexpr unsigned char kSegments[10] = {
    0b0111111,  // 0: a b c d e f
    0b0000110,  // 1: b c
    0b1011011,  // 2: a b d e g
    0b1001111,  // 3: a b c d g
    0b1100110,  // 4: b c f g
    0b1101101,  // 5: a c d f g
    0b1111101,  // 6: a c d e f g
    0b0000111,  // 7: a b c
    0b1111111,  // 8: all
    0b1101111,  // 9: a b c d f g
};

struct Box
{
  double u0, v0, u1, v1;
};

/// Width of one character in units of the height; negative for characters not drawn.
double charWidth(char c)
{
  if (c >= '0' && c <= '9')
  {
    return 0.5;
  }
  switch (c)
  {
    case '.': return 0.125;
    case 'm': return 0.5;
    case ' ': return 0.5;
    default: return -1.0;
  }
}

constexpr double kGap = 0.2;     // between characters, in heights
constexpr double kStroke = 0.125;  // in heights

/// The boxes of character `c` in units of the height, (u, v) from its bottom-left corner.
int boxesOf(char c, Box* boxes)
{
  const double w = 0.5, t = kStroke, h = 1.0, m = 0.5;
  int n = 0;
  if (c >= '0' && c <= '9')
  {
    const Box segment[7] = {
        {0, h - t, w, h},                    // a
        {w - t, m, w, h},                    // b
        {w - t, 0, w, m},                    // c
        {0, 0, w, t},                        // d
        {0, 0, t, m},                        // e
        {0, m, t, h},                        // f
        {0, m - 0.5 * t, w, m + 0.5 * t},   // g
    };
    for (int i = 0; i < 7; ++i)
    {
      if (kSegments[c - '0'] & (1u << i))
      {
        boxes[n++] = segment[i];
      }
    }
  }
  else if (c == '.')
  {
    boxes[n++] = {0, 0, t, t};
  }
  else if (c == 'm')
  {
    boxes[n++] = {0, 0, t, m};                              // left leg
    boxes[n++] = {0.5 * (w - t), 0, 0.5 * (w + t), m};      // middle leg
    boxes[n++] = {w - t, 0, w, m};                          // right leg
    boxes[n++] = {0, m - t, w, m};                          // top bar
  }
  return n;
}
}  // namespace

double digitTextWidth(const std::string& text, double height)
{
  double width = 0.0;
  int drawn = 0;
  for (const char c : text)
  {
    const double w = charWidth(c);
    if (w >= 0.0)
    {
      width += w + (drawn > 0 ? kGap : 0.0);
      ++drawn;
    }
  }
  return width * height;
}

int appendDigitTriangles(const std::string& text, const Vec2& origin, double height, const Vec2& direction,
                         std::vector<Vec2>& out)
{
  const double length = norm(direction);
  if (!isFinite(origin) || !std::isfinite(height) || !(height > 0.0) || !std::isfinite(length) || !(length > 0.0))
  {
    return 0;
  }
  const Vec2 along = direction * (1.0 / length);
  const Vec2 up = perpendicular(along);
  int drawn = 0;
  double pen = 0.0;  // in heights, from origin along the reading direction
  for (const char c : text)
  {
    const double w = charWidth(c);
    if (w < 0.0)
    {
      continue;
    }
    Box boxes[7];
    const int n = boxesOf(c, boxes);
    for (int i = 0; i < n; ++i)
    {
      const Box& b = boxes[i];
      const auto at = [&](double u, double v) { return origin + along * ((pen + u) * height) + up * (v * height); };
      // (u0,v0) (u1,v0) (u1,v1) (u0,v1) is counter-clockwise in (along, up), a right-handed frame.
      const Vec2 p0 = at(b.u0, b.v0), p1 = at(b.u1, b.v0), p2 = at(b.u1, b.v1), p3 = at(b.u0, b.v1);
      out.insert(out.end(), {p0, p1, p2, p0, p2, p3});
    }
    pen += w + kGap;
    ++drawn;
  }
  return drawn;
}

std::vector<Vec2> digitTriangles(const std::string& text, const Vec2& origin, double height, const Vec2& direction)
{
  std::vector<Vec2> out;
  appendDigitTriangles(text, origin, height, direction, out);
  return out;
}
}  // namespace rviz_projector
