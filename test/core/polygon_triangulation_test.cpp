// Triangulation of polygons with holes, judged by hand: the triangles' areas add up to the polygon's
// area computed by hand, every triangle is counter-clockwise, and sample points are covered exactly
// once inside the polygon and never in a hole or outside.
#include "rviz_projector/core/polygon_triangulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <vector>

namespace rviz_projector
{
namespace
{
double cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

int coverCount(const std::vector<Vec2>& triangles, const Vec2& p)
{
  int count = 0;
  for (std::size_t i = 0; i + 2 < triangles.size(); i += 3)
  {
    const Vec2 &a = triangles[i], &b = triangles[i + 1], &c = triangles[i + 2];
    if (cross(b - a, p - a) > 0 && cross(c - b, p - b) > 0 && cross(a - c, p - c) > 0)
    {
      ++count;
    }
  }
  return count;
}

double area(const std::vector<Vec2>& triangles)
{
  double sum = 0.0;
  for (std::size_t i = 0; i + 2 < triangles.size(); i += 3)
  {
    const double twice = cross(triangles[i + 1] - triangles[i], triangles[i + 2] - triangles[i]);
    EXPECT_GT(twice, 0.0) << "triangle " << i / 3 << " not counter-clockwise";
    sum += 0.5 * twice;
  }
  return sum;
}

/// Every point of a grid (off every edge and diagonal) covered once where `inside` says so,
/// never elsewhere.
void expectCoveredOnce(const std::vector<Vec2>& triangles, const std::function<bool(const Vec2&)>& inside)
{
  for (double x = -0.495; x < 3.0; x += 0.05)
  {
    for (double y = -0.4863; y < 3.0; y += 0.05)  // never on a diagonal x = y + c of the shapes
    {
      EXPECT_EQ(inside({x, y}) ? 1 : 0, coverCount(triangles, {x, y})) << x << ", " << y;
    }
  }
}

TEST(PolygonTriangulation, SquareWithASquareHole)
{
  // 2 x 2 square minus a 1 x 1 hole in its middle: 3 m^2.
  const std::vector<Vec2> outer{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const std::vector<Vec2> hole{{0.5, 0.5}, {1.5, 0.5}, {1.5, 1.5}, {0.5, 1.5}};
  const std::vector<Vec2> triangles = triangulatePolygon(outer, {hole});
  EXPECT_NEAR(3.0, area(triangles), 1e-12);
  expectCoveredOnce(triangles, [](const Vec2& p) {
    const bool in_square = p.x > 0 && p.x < 2 && p.y > 0 && p.y < 2;
    const bool in_hole = p.x > 0.5 && p.x < 1.5 && p.y > 0.5 && p.y < 1.5;
    return in_square && !in_hole;
  });
}

TEST(PolygonTriangulation, ClockwiseConcaveCombWithTwoHoles)
{
  // A comb (clockwise): a 3 x 1 base with two 0.5 x 1.5 teeth at x 0..0.5 and 2.5..3; area
  // 3 + 2 * 0.75 = 4.5, minus two 0.2 x 0.2 holes in the base.
  std::vector<Vec2> comb{{0, 0}, {3, 0}, {3, 2.5}, {2.5, 2.5}, {2.5, 1}, {0.5, 1}, {0.5, 2.5}, {0, 2.5}};
  std::reverse(comb.begin(), comb.end());
  const std::vector<Vec2> hole_a{{1, 0.4}, {1.2, 0.4}, {1.2, 0.6}, {1, 0.6}};
  const std::vector<Vec2> hole_b{{2, 0.4}, {2, 0.6}, {2.2, 0.6}, {2.2, 0.4}};  // either orientation
  const std::vector<Vec2> triangles = triangulatePolygon(comb, {hole_a, hole_b});
  EXPECT_NEAR(4.5 - 0.08, area(triangles), 1e-12);
  expectCoveredOnce(triangles, [](const Vec2& p) {
    const bool base = p.x > 0 && p.x < 3 && p.y > 0 && p.y < 1;
    const bool teeth = p.y >= 1 && p.y < 2.5 && ((p.x > 0 && p.x < 0.5) || (p.x > 2.5 && p.x < 3));
    const bool holes = p.y > 0.4 && p.y < 0.6 && ((p.x > 1 && p.x < 1.2) || (p.x > 2 && p.x < 2.2));
    return (base || teeth) && !holes;
  });
}

TEST(PolygonTriangulation, DegenerateInputGivesNothingOrWhatIsThere)
{
  EXPECT_TRUE(triangulatePolygon({}).empty());
  EXPECT_TRUE(triangulatePolygon({{0, 0}, {1, 1}}).empty());
  EXPECT_TRUE(triangulatePolygon({{0, 0}, {1, 1}, {2, 2}}).empty()) << "no area";
  // Collinear points along an edge add no triangle of their own.
  const std::vector<Vec2> triangles = triangulatePolygon({{0, 0}, {0.5, 0}, {1, 0}, {1, 1}, {0, 1}});
  EXPECT_NEAR(1.0, area(triangles), 1e-12);
  EXPECT_TRUE(insidePolygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {0.5, 0.5}));
  EXPECT_FALSE(insidePolygon({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {1.5, 0.5}));
}
}  // namespace
}  // namespace rviz_projector
