// Seven-segment floor text against boxes worked out by hand: a digit is 0.5 h wide, strokes h / 8,
// characters 0.2 h apart, '.' an h / 8 square on the baseline, 'm' half the height tall.
#include "rviz_projector/core/digit_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rviz_projector
{
namespace
{
bool covered(const std::vector<Vec2>& triangles, const Vec2& p)
{
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
  {
    const Vec2 &a = triangles[t], &b = triangles[t + 1], &c = triangles[t + 2];
    const auto side = [](const Vec2& o, const Vec2& u, const Vec2& v) {
      return (u.x - o.x) * (v.y - o.y) - (u.y - o.y) * (v.x - o.x);
    };
    if (side(a, b, p) >= 0 && side(b, c, p) >= 0 && side(c, a, p) >= 0)
    {
      return true;  // counter-clockwise triangles only: a clockwise one covers nothing here
    }
  }
  return false;
}

TEST(DigitText, EightLightsEverySegmentAndLeavesItsHoles)
{
  const std::vector<Vec2> t = digitTriangles("8", {0, 0}, 1.0, {1, 0});
  EXPECT_EQ(t.size(), 7u * 6u);  // seven segments, two triangles each
  // Segment centres (u, v): a (0.25, 0.9375), b (0.4375, 0.75), c (0.4375, 0.25), d (0.25, 0.0625),
  // e (0.0625, 0.25), f (0.0625, 0.75), g (0.25, 0.5).
  for (const Vec2& p : {Vec2{0.25, 0.9375}, Vec2{0.4375, 0.75}, Vec2{0.4375, 0.25}, Vec2{0.25, 0.0625},
                        Vec2{0.0625, 0.25}, Vec2{0.0625, 0.75}, Vec2{0.25, 0.5}})
  {
    EXPECT_TRUE(covered(t, p)) << p.x << ", " << p.y;
  }
  // The two holes, (0.25, 0.25) and (0.25, 0.75), and outside the 0.5 x 1 cell.
  EXPECT_FALSE(covered(t, {0.25, 0.25}));
  EXPECT_FALSE(covered(t, {0.25, 0.75}));
  EXPECT_FALSE(covered(t, {0.55, 0.5}));
  EXPECT_FALSE(covered(t, {0.25, 1.05}));
}

TEST(DigitText, OneZeroAndSixUseTheirSegments)
{
  const std::vector<Vec2> one = digitTriangles("1", {0, 0}, 1.0, {1, 0});
  EXPECT_EQ(one.size(), 2u * 6u);  // b, c
  EXPECT_TRUE(covered(one, {0.4375, 0.25}));
  EXPECT_FALSE(covered(one, {0.0625, 0.25}));  // no e
  EXPECT_FALSE(covered(one, {0.25, 0.9375}));  // no a
  const std::vector<Vec2> zero = digitTriangles("0", {0, 0}, 1.0, {1, 0});
  EXPECT_FALSE(covered(zero, {0.25, 0.5}));  // no g
  EXPECT_TRUE(covered(zero, {0.25, 0.0625}));
  const std::vector<Vec2> six = digitTriangles("6", {0, 0}, 1.0, {1, 0});
  EXPECT_FALSE(covered(six, {0.4375, 0.75}));  // no b
  EXPECT_TRUE(covered(six, {0.0625, 0.25}));   // e
}

TEST(DigitText, CharactersFollowEachOtherAlongTheReadingDirection)
{
  // "1." at height 0.1 reading along +y: up is the left of +y, i.e. -x. The '.' starts at pen
  // 0.5 + 0.2 = 0.7 heights = 0.07 m: its square spans y in [0.07, 0.0825], x in [-0.0125, 0].
  const std::vector<Vec2> t = digitTriangles("1.", {0, 0}, 0.1, {0, 2});
  EXPECT_TRUE(covered(t, {-0.00625, 0.07625}));
  EXPECT_FALSE(covered(t, {0.00625, 0.07625}));  // below the baseline
  EXPECT_FALSE(covered(t, {-0.00625, 0.09}));    // past the dot
  // The '1' at u in [0.4375, 0.5] h -> y in [0.04375, 0.05], v in [0, 1] h -> x in [-0.1, 0].
  EXPECT_TRUE(covered(t, {-0.05, 0.047}));
  // Widths: "1." = 0.5 + 0.2 + 0.125 heights; "0.6 m" = 4 x 0.5 + 0.125 + 4 x 0.2 = 2.925 heights.
  EXPECT_NEAR(digitTextWidth("1.", 0.1), 0.0825, 1e-12);
  EXPECT_NEAR(digitTextWidth("0.6 m", 0.1), 0.2925, 1e-12);
  // 'm': three legs and a top bar, half the height: leg centres v = 0.25, bar at v in [0.375, 0.5].
  const std::vector<Vec2> m = digitTriangles("m", {0, 0}, 1.0, {1, 0});
  EXPECT_EQ(m.size(), 4u * 6u);
  EXPECT_TRUE(covered(m, {0.25, 0.25}));
  EXPECT_TRUE(covered(m, {0.125, 0.45}));
  EXPECT_FALSE(covered(m, {0.15, 0.25}));  // between the left leg (to 0.125) and the middle (from 0.1875)
  EXPECT_FALSE(covered(m, {0.25, 0.6}));
}

TEST(DigitText, TrianglesAreCounterClockwise)
{
  const std::vector<Vec2> t = digitTriangles("0123456789.m", {3, -2}, 0.2, {-1, 1});
  ASSERT_FALSE(t.empty());
  for (std::size_t i = 0; i + 2 < t.size(); i += 3)
  {
    const Vec2 u = t[i + 1] - t[i], v = t[i + 2] - t[i];
    EXPECT_GT(u.x * v.y - u.y * v.x, 0.0) << i;
  }
}

TEST(DigitText, BadInputDrawsNothingAndUnknownCharactersAreSkipped)
{
  std::vector<Vec2> out;
  EXPECT_EQ(appendDigitTriangles("8", {std::nan(""), 0}, 1.0, {1, 0}, out), 0);
  EXPECT_EQ(appendDigitTriangles("8", {0, 0}, 0.0, {1, 0}, out), 0);
  EXPECT_EQ(appendDigitTriangles("8", {0, 0}, -1.0, {1, 0}, out), 0);
  EXPECT_EQ(appendDigitTriangles("8", {0, 0}, INFINITY, {1, 0}, out), 0);
  EXPECT_EQ(appendDigitTriangles("8", {0, 0}, 1.0, {0, 0}, out), 0);
  EXPECT_EQ(appendDigitTriangles("8", {0, 0}, 1.0, {std::nan(""), 1}, out), 0);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(appendDigitTriangles("x8?", {0, 0}, 1.0, {1, 0}, out), 1);
  const std::vector<Vec2> eight = digitTriangles("8", {0, 0}, 1.0, {1, 0});
  ASSERT_EQ(out.size(), eight.size());
  for (std::size_t i = 0; i < out.size(); ++i)
  {
    EXPECT_EQ(out[i].x, eight[i].x);
    EXPECT_EQ(out[i].y, eight[i].y);
  }
  EXPECT_EQ(digitTextWidth("x8?", 1.0), 0.5);
}
}  // namespace
}  // namespace rviz_projector
