// The projection mask's occluders drawn once (core occluder_union.h): the union's top covers
// exactly the floor points inside some column's square and its walls stand on the union's outline,
// facing out, judged against the squares by hand (a point is inside a square when |x - cx| < m and
// |y - cy| < m), never against the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rviz_projector/core/occluder_union.h"

using namespace rviz_projector;

namespace
{
struct Square
{
  Vec2 c;
  double m;
};

bool insideSquares(const std::vector<Square>& squares, double x, double y)
{
  for (const Square& s : squares)
  {
    if (std::abs(x - s.c.x) < s.m && std::abs(y - s.c.y) < s.m)
    {
      return true;
    }
  }
  return false;
}

bool insideTriangle(const Vec3& a, const Vec3& b, const Vec3& c, double x, double y)
{
  const auto side = [](const Vec3& p, const Vec3& q, double px, double py) {
    return (q.x - p.x) * (py - p.y) - (q.y - p.y) * (px - p.x);
  };
  const double d1 = side(a, b, x, y), d2 = side(b, c, x, y), d3 = side(c, a, x, y);
  return d1 > 0 && d2 > 0 && d3 > 0;
}

/// How many top triangles (z == height, normal +z) contain the floor point.
int topCover(const std::vector<MeshVertex>& t, double height, double x, double y)
{
  int n = 0;
  for (std::size_t i = 0; i + 2 < t.size(); i += 3)
  {
    if (t[i].normal.z == 1.0 && t[i].position.z == height && t[i + 1].position.z == height &&
        t[i + 2].position.z == height && insideTriangle(t[i].position, t[i + 1].position, t[i + 2].position, x, y))
    {
      ++n;
    }
  }
  return n;
}

/// Checks the union of `squares` (all of half-width given per square) at `height`.
void expectUnionOf(const std::vector<Square>& squares, double height, double probe_step)
{
  std::vector<std::vector<Vec2>> sets_points;
  std::vector<OccluderSquares> sets;
  sets_points.reserve(squares.size());
  for (const Square& s : squares)
  {
    sets_points.push_back({s.c});
  }
  for (std::size_t i = 0; i < squares.size(); ++i)
  {
    sets.push_back({&sets_points[i], squares[i].m});
  }
  OccluderUnion u;
  ASSERT_TRUE(u.build(sets, height));
  EXPECT_EQ(u.squares(), squares.size());
  const std::vector<MeshVertex>& t = u.triangles();
  ASSERT_EQ(t.size() % 3, 0u);
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9;
  for (const Square& s : squares)
  {
    x0 = std::min(x0, s.c.x - s.m - 0.05);
    x1 = std::max(x1, s.c.x + s.m + 0.05);
    y0 = std::min(y0, s.c.y - s.m - 0.05);
    y1 = std::max(y1, s.c.y + s.m + 0.05);
  }
  // The top: every probe (off the squares' edges by construction of the odd step) is covered once
  // when inside a square, never otherwise.
  int inside = 0;
  for (double x = x0 + 0.00037; x < x1; x += probe_step)
  {
    for (double y = y0 + 0.00041; y < y1; y += probe_step)
    {
      const bool want = insideSquares(squares, x, y);
      inside += want ? 1 : 0;
      ASSERT_EQ(topCover(t, height, x, y), want ? 1 : 0) << "floor point " << x << ", " << y;
    }
  }
  EXPECT_GT(inside, 0);
  // The walls: vertical quads from 0 to height whose outward normal (unit, horizontal) points out
  // of the union: just outside the middle of each wall's foot no square, just inside one.
  int walls = 0;
  for (std::size_t i = 0; i + 2 < t.size(); i += 3)
  {
    const Vec3& n = t[i].normal;
    if (n.z != 0.0)
    {
      continue;
    }
    ++walls;
    EXPECT_NEAR(std::hypot(n.x, n.y), 1.0, 1e-12);
    const Vec3 &a = t[i].position, &b = t[i + 1].position, &c = t[i + 2].position;
    // Counter-clockwise seen from outside: (b - a) x (c - a) along the normal.
    const Vec3 u1{b.x - a.x, b.y - a.y, b.z - a.z}, u2{c.x - a.x, c.y - a.y, c.z - a.z};
    const Vec3 cross{u1.y * u2.z - u1.z * u2.y, u1.z * u2.x - u1.x * u2.z, u1.x * u2.y - u1.y * u2.x};
    EXPECT_GT(cross.x * n.x + cross.y * n.y, 0.0) << "wall triangle " << i / 3 << " faces in";
    if (a.z == 0.0 && b.z == 0.0)  // the first triangle of a wall: a, b on the floor, c on top
    {
      EXPECT_EQ(c.z, height);
      const double mx = 0.5 * (a.x + b.x), my = 0.5 * (a.y + b.y);
      EXPECT_FALSE(insideSquares(squares, mx + 1e-3 * n.x, my + 1e-3 * n.y)) << "outside wall " << i / 6;
      EXPECT_TRUE(insideSquares(squares, mx - 1e-3 * n.x, my - 1e-3 * n.y)) << "inside wall " << i / 6;
    }
  }
  EXPECT_GT(walls, 0);
}
}  // namespace

TEST(OccluderUnion, OneSquareIsOneColumn)
{
  // Four walls and a top: 4 * 2 + 2 triangles, as OccluderMesh's column.
  expectUnionOf({{{1.0, -2.0}, 0.1}}, 2.0, 0.013);
  OccluderUnion u;
  const std::vector<Vec2> one{{1.0, -2.0}};
  ASSERT_TRUE(u.build({{&one, 0.1}}, 2.0));
  EXPECT_EQ(u.triangles().size(), 30u);
}

TEST(OccluderUnion, AScanOfAPersonIsItsOutlineOnceNotFiftyColumns)
{
  // ~50 returns 1 cm apart on a leg's arc (what the demo's scan gives), 10 cm margins.
  std::vector<Square> squares;
  for (int i = 0; i < 50; ++i)
  {
    const double a = -0.6 + 1.2 * i / 49.0;
    squares.push_back({{2.0 - 0.25 * std::cos(a), 0.5 + 0.25 * std::sin(a)}, 0.1});
  }
  expectUnionOf(squares, 2.0, 0.0071);
  std::vector<Vec2> points;
  for (const Square& s : squares)
  {
    points.push_back(s.c);
  }
  OccluderUnion u;
  ASSERT_TRUE(u.build({{&points, 0.1}}, 2.0));
  // Overdraw: a line of sight across the person at y = 0.5 meets the columns' walls ~2 x 40 times
  // (every square it crosses), the union's twice (in and out).
  int crossings = 0;
  const std::vector<MeshVertex>& t = u.triangles();
  for (std::size_t i = 0; i + 2 < t.size(); i += 3)
  {
    const Vec3 &a = t[i].position, &b = t[i + 1].position;
    if (t[i].normal.z == 0.0 && a.z == 0.0 && b.z == 0.0 && (a.y - 0.5) * (b.y - 0.5) < 0.0)
    {
      ++crossings;
    }
  }
  EXPECT_EQ(crossings, 2) << "walls crossed by the line y = 0.5";
}

TEST(OccluderUnion, ARingOfSquaresHasAHoleWhoseWallsFaceIntoIt)
{
  // 12 squares around a 1 m circle, overlapping: an annulus (one outer ring, one hole).
  std::vector<Square> squares;
  for (int i = 0; i < 12; ++i)
  {
    const double a = 2 * 3.14159265358979323846 * i / 12;
    squares.push_back({{std::cos(a), std::sin(a)}, 0.3});
  }
  expectUnionOf(squares, 1.5, 0.017);
  EXPECT_FALSE(insideSquares(squares, 0.0, 0.0)) << "the test's own premise: the centre is a hole";
}

TEST(OccluderUnion, RandomSquaresOfTwoSizesAgreeWithTheSquares)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-1.0, 1.0);
  for (int run = 0; run < 5; ++run)
  {
    // Centres on a 1 cm lattice and margins of whole 5 mm: every edge on a 5 mm lattice, so the
    // 1 mm probes beside a wall never land in a gap narrower than they reach.
    const auto lattice = [&] { return std::round(at(rng) * 100.0) / 100.0; };
    std::vector<Square> squares;
    for (int i = 0; i < 25; ++i)
    {
      squares.push_back({{lattice(), lattice()}, i % 2 ? 0.1 : 0.175});
    }
    expectUnionOf(squares, 2.0, 0.031);
  }
}

TEST(OccluderUnion, BadInputIsSkippedOrRefused)
{
  OccluderUnion u;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Vec2> mixed{{nan, 0.0}, {1.0, 1.0}, {0.0, std::numeric_limits<double>::infinity()}};
  ASSERT_TRUE(u.build({{&mixed, 0.1}}, 2.0));
  EXPECT_EQ(u.squares(), 1u) << "non-finite points skipped";
  EXPECT_EQ(u.triangles().size(), 30u);
  for (double margin : {0.0, -0.1, nan})
  {
    ASSERT_TRUE(u.build({{&mixed, margin}}, 2.0));
    EXPECT_TRUE(u.triangles().empty()) << "margin " << margin;
  }
  for (double height : {0.0, -1.0, nan})
  {
    ASSERT_TRUE(u.build({{&mixed, 0.1}}, height));
    EXPECT_TRUE(u.triangles().empty()) << "height " << height;
    EXPECT_EQ(u.squares(), 0u);
  }
  ASSERT_TRUE(u.build({{nullptr, 0.1}}, 2.0));
  EXPECT_TRUE(u.triangles().empty());
  // Beyond Clipper's reach, or too many squares: refused (the caller draws the columns).
  const std::vector<Vec2> far{{0.0, 0.0}, {2e6, 0.0}};
  EXPECT_FALSE(u.build({{&far, 0.1}}, 2.0));
  EXPECT_TRUE(u.triangles().empty());
  std::vector<Vec2> many(OccluderUnion::kMaxSquares + 1, Vec2{0.5, 0.5});
  EXPECT_FALSE(u.build({{&many, 0.1}}, 2.0));
  many.pop_back();
  EXPECT_TRUE(u.build({{&many, 0.1}}, 2.0)) << "kMaxSquares squares are still merged";
  EXPECT_EQ(u.triangles().size(), 30u) << "all on one spot: one column";
  // Far from the map's origin (a robot 100 km out): the union is formed around its first square.
  const std::vector<Vec2> away{{1e5, -1e5}, {1e5 + 0.05, -1e5}};
  ASSERT_TRUE(u.build({{&away, 0.1}}, 2.0));
  EXPECT_EQ(u.triangles().size(), 30u) << "two overlapping squares along x: one box";
}
