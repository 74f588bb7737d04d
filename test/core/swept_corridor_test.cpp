// The swept corridor (issue 25) against envelopes computed by hand: a rectangle driving straight,
// a circle and a rectangle driving round an arc (the rectangle's outer rim is traced by its front
// corner, sqrt(front^2 + (R + half width)^2) from the centre, its inner rim by the middle of its
// inner side, R - half width: not a fixed offset of the centre line), a non-convex footprint whose
// notch stays unswept, the clip at the destination, and the footprints that are refused.
#include "rviz_projector/core/swept_corridor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rviz_projector/core/path_location.h"

namespace rviz_projector
{
namespace
{
// A rectangular robot: 0.4 m ahead of its centre, 0.2 m behind, 0.3 m to each side.
const std::vector<Vec2> kRectangle{{0.4, 0.3}, {-0.2, 0.3}, {-0.2, -0.3}, {0.4, -0.3}};

struct Path
{
  std::vector<Vec2> points;
  std::vector<double> lengths;
};

Path straightPath(double length)
{
  Path path;
  for (int i = 0; i <= 100; ++i)
  {
    path.points.push_back({length * i / 100.0, 0.0});
  }
  accumulateArcLengths(path.points, path.lengths);
  return path;
}

/// Counter-clockwise (turning left) round the circle of `radius` about (0, radius), from the origin.
Path arcPath(double radius, double angle)
{
  Path path;
  const int n = int(std::ceil(radius * angle / 0.01));
  for (int i = 0; i <= n; ++i)
  {
    const double a = angle * i / n;
    path.points.push_back({radius * std::sin(a), radius - radius * std::cos(a)});
  }
  accumulateArcLengths(path.points, path.lengths);
  return path;
}

bool inTriangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c)
{
  auto side = [](const Vec2& o, const Vec2& u, const Vec2& v) { return (u.x - o.x) * (v.y - o.y) - (u.y - o.y) * (v.x - o.x); };
  const double d1 = side(a, b, p), d2 = side(b, c, p), d3 = side(c, a, p);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
}

bool covered(const std::vector<Vec2>& triangles, const Vec2& p)
{
  for (std::size_t i = 0; i + 2 < triangles.size(); i += 3)
  {
    if (inTriangle(p, triangles[i], triangles[i + 1], triangles[i + 2]))
    {
      return true;
    }
  }
  return false;
}

/// The corridor of `footprint` along `path` from arc length `start`, `length` metres, default
/// parameters otherwise.
SweptCorridor sweep(const Path& path, double start, const std::vector<Vec2>& footprint, double length,
                    double heading_chord = CorridorParameters().heading_chord)
{
  SweptCorridor corridor;
  CorridorParameters parameters;
  parameters.length = length;
  parameters.heading_chord = heading_chord;
  corridor.build(path.points, path.lengths, start, footprint, parameters);
  return corridor;
}

TEST(SweptCorridor, StraightRectangleSweepsARectangle)
{
  const Path path = straightPath(5.0);
  const SweptCorridor corridor = sweep(path, 1.0, kRectangle, 2.0);
  // By hand: the robot's centre goes from x = 1 to x = 3; its body covers x in [0.8, 3.4], |y| <= 0.3.
  ASSERT_EQ(2u, corridor.edgeLines().size());
  for (const std::vector<Vec2>& line : corridor.edgeLines())
  {
    ASSERT_GE(line.size(), 2u);
    double low = INFINITY, high = -INFINITY;
    for (const Vec2& p : line)
    {
      EXPECT_NEAR(0.3, std::abs(p.y), 1e-4) << p.x << ", " << p.y;
      EXPECT_NEAR(line.front().y, p.y, 1e-4) << "an edge stays on its side";
      low = std::min(low, p.x);
      high = std::max(high, p.x);
    }
    EXPECT_NEAR(0.8, low, 1e-4);
    EXPECT_NEAR(3.4, high, 1e-4);
    EXPECT_LT(line.front().x, line.back().x) << "edges run in the direction of travel";
  }
  EXPECT_GT(corridor.edgeLines()[0].front().y * corridor.edgeLines()[1].front().y, -1.0);
  EXPECT_LT(corridor.edgeLines()[0].front().y * corridor.edgeLines()[1].front().y, 0.0) << "one edge each side";
  for (const Vec2& p : {Vec2{0.81, 0.29}, Vec2{2.0, 0.0}, Vec2{3.39, -0.29}})
  {
    EXPECT_TRUE(covered(corridor.band(), p)) << p.x << ", " << p.y;
  }
  for (const Vec2& p : {Vec2{0.79, 0.0}, Vec2{2.0, 0.31}, Vec2{3.41, 0.0}})
  {
    EXPECT_FALSE(covered(corridor.band(), p)) << p.x << ", " << p.y;
  }
  // Edge lines of 3 cm: every triangle vertex within 1.5 cm of the rim.
  for (const Vec2& v : corridor.edges())
  {
    EXPECT_NEAR(0.3, std::abs(v.y), 0.015 + 1e-4);
  }
}

TEST(SweptCorridor, CircleRoundAnArcSweepsTwoConcentricArcs)
{
  const double radius = 2.0, robot = 0.25;
  const Path path = arcPath(radius, 1.5);
  SweptCorridor corridor;
  CorridorParameters parameters;
  parameters.length = 2.0;
  corridor.buildRound(path.points, path.lengths, 0.5, robot, parameters);
  ASSERT_EQ(2u, corridor.edgeLines().size());
  const Vec2 centre{0.0, radius};
  int inner = 0, outer = 0;
  for (const std::vector<Vec2>& line : corridor.edgeLines())
  {
    // Each line's two ends are where the round caps were cut off: judged by the points between.
    for (std::size_t i = 1; i + 1 < line.size(); ++i)
    {
      const Vec2& p = line[i];
      const double r = distance(p, centre);
      // Clipper's round offset: arcs within 0.1 mm; cleaning merges points 0.5 mm apart.
      if (r < radius)
      {
        EXPECT_NEAR(radius - robot, r, 0.6e-3);
        ++inner;
      }
      else
      {
        EXPECT_NEAR(radius + robot, r, 0.6e-3);
        ++outer;
      }
    }
  }
  EXPECT_GT(inner, 10);
  EXPECT_GT(outer, 10);
  // The band: the robot's centre is at path angle 0.25 .. 1.25 rad; at 0.75 rad the band spans
  // radii 1.75 .. 2.25.
  for (const double r : {1.76, 2.0, 2.24})
  {
    EXPECT_TRUE(covered(corridor.band(), centre + Vec2{r * std::sin(0.75), -r * std::cos(0.75)})) << r;
  }
  for (const double r : {1.74, 2.26})
  {
    EXPECT_FALSE(covered(corridor.band(), centre + Vec2{r * std::sin(0.75), -r * std::cos(0.75)})) << r;
  }
}

TEST(SweptCorridor, RectangleRoundAnArcIsNotAFixedOffset)
{
  const double radius = 2.0;
  const Path path = arcPath(radius, 1.5);
  SweptCorridor corridor;
  CorridorParameters parameters;
  parameters.length = 2.0;
  const double start = 0.5;
  corridor.build(path.points, path.lengths, start, kRectangle, parameters);
  ASSERT_EQ(2u, corridor.edgeLines().size());
  const Vec2 centre{0.0, radius};
  // By hand, turning left round the centre: the outer (right) rim is traced by the front right
  // corner, sqrt(0.4^2 + 2.3^2) = 2.33452 m from the centre; the inner (left) rim by the middle of
  // the left side, 2 - 0.3 = 1.7 m. Judged where the robot is well inside the arc (angles of the
  // robot's centre from 0.5 + 0.3 to 2.5 - 0.3 m of path).
  const double outer = std::sqrt(0.4 * 0.4 + 2.3 * 2.3);
  int judged = 0;
  double widest = 0.0;
  for (const std::vector<Vec2>& line : corridor.edgeLines())
  {
    for (const Vec2& p : line)
    {
      const double angle = std::atan2(p.x - centre.x, centre.y - p.y);  // 0 at the origin, growing along the path
      const double r = distance(p, centre);
      widest = std::max(widest, r);
      if (angle < (start + 0.45) / radius || angle > (start + 2.0 - 0.05) / radius)
      {
        continue;
      }
      ++judged;
      EXPECT_NEAR(r < radius ? 1.7 : outer, r, 1e-3) << "at " << angle << " rad";
    }
  }
  EXPECT_GT(judged, 10);
  EXPECT_NEAR(outer, widest, 1e-3);
}

double bandArea(const std::vector<Vec2>& triangles)
{
  double area = 0.0;
  for (std::size_t i = 0; i + 2 < triangles.size(); i += 3)
  {
    const Vec2 &a = triangles[i], &b = triangles[i + 1], &c = triangles[i + 2];
    area += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
  }
  return area;
}

std::vector<Vec2> regularPolygon(int n, double radius)
{
  std::vector<Vec2> polygon;
  for (int i = 0; i < n; ++i)
  {
    polygon.push_back({radius * std::cos(2.0 * M_PI * i / n), radius * std::sin(2.0 * M_PI * i / n)});
  }
  return polygon;
}

TEST(SweptCorridor, RoundRobotPublishedAsAPolygonSweepsItsHullOnAStraight)
{
  // A round robot as move_base publishes its footprint: a 24-gon of radius 0.3 (vertices at 0, 15,
  // ... degrees, so one at 90 and one at 270). By hand, driving 2 m straight along x from x = 1: the
  // swept area is the polygon's area, n/2 r^2 sin(2 pi / n), plus its width 2r times 2 m, between
  // the rims y = +-0.3 from x = 1 to x = 3.
  const Path path = straightPath(5.0);
  const SweptCorridor corridor = sweep(path, 1.0, regularPolygon(24, 0.3), 2.0);
  const double expected = 12.0 * 0.09 * std::sin(2.0 * M_PI / 24.0) + 0.6 * 2.0;
  EXPECT_NEAR(expected, bandArea(corridor.band()), 1e-4);
  ASSERT_EQ(2u, corridor.edgeLines().size());
  for (const std::vector<Vec2>& line : corridor.edgeLines())
  {
    double low = INFINITY, high = -INFINITY;
    for (const Vec2& p : line)
    {
      EXPECT_LE(std::abs(p.y), 0.3 + 1e-4) << p.x << ", " << p.y;
      if (std::abs(std::abs(p.y) - 0.3) < 1e-4)
      {
        low = std::min(low, p.x);
        high = std::max(high, p.x);
      }
    }
    EXPECT_NEAR(1.0, low, 1e-4) << "the rim leaves the robot's side where it starts";
    EXPECT_NEAR(3.0, high, 1e-4) << "and reaches the side of the robot at its last place";
  }
  for (const Vec2& p : {Vec2{1.0, 0.299}, Vec2{2.0, -0.299}, Vec2{3.299, 0.0}, Vec2{0.701, 0.0}})
  {
    EXPECT_TRUE(covered(corridor.band(), p)) << p.x << ", " << p.y;
  }
  for (const Vec2& p : {Vec2{2.0, 0.301}, Vec2{3.301, 0.0}, Vec2{0.699, 0.0}})
  {
    EXPECT_FALSE(covered(corridor.band(), p)) << p.x << ", " << p.y;
  }
}

TEST(SweptCorridor, StraightIntoAnArcIsExactOnBoth)
{
  // 1 m straight along x, then a left turn of radius 2 about (1, 2). The rectangle starts at x = 0.5
  // and sweeps 3 m: by hand, on the straight (centre x <= 1) its rims are y = +-0.3; well inside the
  // arc the inner rim is 2 - 0.3 = 1.7 m from the centre of the turn, the outer one is traced by the
  // front right corner, sqrt(0.4^2 + 2.3^2) m from it.
  Path path;
  for (int i = 0; i <= 100; ++i)
  {
    path.points.push_back({0.01 * i, 0.0});
  }
  for (int i = 1; i <= 300; ++i)
  {
    const double a = 1.5 * i / 300;
    path.points.push_back({1.0 + 2.0 * std::sin(a), 2.0 - 2.0 * std::cos(a)});
  }
  accumulateArcLengths(path.points, path.lengths);
  const SweptCorridor corridor = sweep(path, 0.5, kRectangle, 3.0);
  ASSERT_EQ(2u, corridor.edgeLines().size());
  const Vec2 centre{1.0, 2.0};
  const double outer = std::sqrt(0.4 * 0.4 + 2.3 * 2.3);
  int straight = 0, arc = 0;
  for (const std::vector<Vec2>& line : corridor.edgeLines())
  {
    for (const Vec2& p : line)
    {
      if (p.x <= 0.7)  // beside the robot while it is on the straight
      {
        ++straight;
        EXPECT_NEAR(0.3, std::abs(p.y), 1e-4) << p.x << ", " << p.y;
        continue;
      }
      const double angle = std::atan2(p.x - centre.x, centre.y - p.y);  // along the turn from x = 1
      if (angle < 0.45 / 2.0 || angle > 2.5 / 2.0 - 0.05)
      {
        continue;  // where the rims change from one to the other, and at the far end
      }
      ++arc;
      const double r = distance(p, centre);
      EXPECT_NEAR(r < 2.0 ? 1.7 : outer, r, 1e-3) << "at " << angle << " rad";
    }
  }
  EXPECT_GT(straight, 1);
  EXPECT_GT(arc, 10);
  // The band covers the centre line from start to end without a gap where the straight meets the arc.
  for (double s = 0.5; s <= 3.5; s += 0.01)
  {
    const Vec2 p = pointAtArcLength(path.points, path.lengths, s);
    EXPECT_TRUE(covered(corridor.band(), p)) << "s = " << s;
  }
}

TEST(SweptCorridor, NonConvexFootprintOnADiagonalStraight)
{
  // The L below, driving 1 m along the diagonal y = x: by hand, in the robot's frame (x along the
  // diagonal, y to its left) the swept area is x in [-0.2, 1.4], |y| <= 0.3, except its notch
  // behind the start (x < 0, y > 0.1), which nothing ever passes.
  const std::vector<Vec2> l_shape{{0.4, 0.3}, {0.0, 0.3}, {0.0, 0.1}, {-0.2, 0.1}, {-0.2, -0.3}, {0.4, -0.3}};
  Path path;
  for (int i = 0; i <= 100; ++i)
  {
    path.points.push_back({0.03 * i, 0.03 * i});
  }
  accumulateArcLengths(path.points, path.lengths);
  const SweptCorridor corridor = sweep(path, 1.0, l_shape, 1.0);
  const Vec2 origin = pointAtArcLength(path.points, path.lengths, 1.0);
  const Vec2 forward{std::sqrt(0.5), std::sqrt(0.5)};
  auto world = [&](double x, double y) { return origin + forward * x + perpendicular(forward) * y; };
  EXPECT_FALSE(covered(corridor.band(), world(-0.1, 0.2))) << "the notch behind the start";
  for (const Vec2& p : {world(-0.19, 0.0), world(-0.1, -0.29), world(0.5, 0.29), world(1.39, -0.29)})
  {
    EXPECT_TRUE(covered(corridor.band(), p));
  }
  for (const Vec2& p : {world(0.5, 0.31), world(0.5, -0.31), world(1.41, 0.0), world(-0.21, 0.0)})
  {
    EXPECT_FALSE(covered(corridor.band(), p));
  }
  const double expected = 0.6 * 1.6 - 0.2 * 0.2;  // the whole rectangle less the notch
  EXPECT_NEAR(expected, bandArea(corridor.band()), 1e-4);
}

TEST(SweptCorridor, NotchInTheSideIsSweptOverByWhatFollowsIt)
{
  // A notch in the left side (x in [-0.1, 0.1], y > 0.2): driving 1 m straight, the part behind it
  // passes over where the notch started, the part ahead of it over where it ends. By hand the
  // swept area is the whole rectangle x in [-0.2, 1.4], |y| <= 0.3 (area 0.96), notches included.
  const std::vector<Vec2> notched{{0.4, 0.3},  {0.1, 0.3},   {0.1, 0.2},   {-0.1, 0.2},
                                  {-0.1, 0.3}, {-0.2, 0.3},  {-0.2, -0.3}, {0.4, -0.3}};
  ASSERT_EQ("", footprintProblem(notched));
  const Path path = straightPath(5.0);
  const SweptCorridor corridor = sweep(path, 0.0, notched, 1.0);
  EXPECT_NEAR(0.96, bandArea(corridor.band()), 1e-4);
  for (const Vec2& p : {Vec2{0.0, 0.29}, Vec2{1.0, 0.29}})
  {
    EXPECT_TRUE(covered(corridor.band(), p)) << "where the notch started and ended: " << p.x << ", " << p.y;
  }
}

TEST(SweptCorridor, ASideStepBetweenTwoPlacesIsFollowed)
{
  // Straight along y = 0 to x = 1, a side step to y = 0.1 by x = 1.05, straight along y = 0.1 on.
  // With a heading chord of 5 cm and steps of 20 cm from s = 0.15 no place sees the side step's
  // heading: every place has heading 0, but they are not all on one line. By hand, the rectangle
  // stays within |y| <= 0.3 while on the first straight (up to s = 0.95, x = 0.95) and within
  // y in [-0.2, 0.4] on the second (from x = 1.15 on): nothing is swept at (0.5, 0.31) or at
  // (2.3, -0.205), which one translation from the first place to the last would cover.
  Path path;
  for (int i = 0; i <= 100; ++i)
  {
    path.points.push_back({0.01 * i, 0.0});
  }
  for (int i = 0; i <= 300; ++i)
  {
    path.points.push_back({1.05 + 0.01 * i, 0.1});
  }
  accumulateArcLengths(path.points, path.lengths);
  const SweptCorridor corridor = sweep(path, 0.15, kRectangle, 2.0, 0.05);
  for (const Vec2& p : {Vec2{0.5, 0.31}, Vec2{2.3, -0.205}})
  {
    EXPECT_FALSE(covered(corridor.band(), p)) << p.x << ", " << p.y;
  }
  for (const Vec2& p : {Vec2{0.5, 0.29}, Vec2{2.3, 0.39}, Vec2{2.3, -0.19}})
  {
    EXPECT_TRUE(covered(corridor.band(), p)) << p.x << ", " << p.y;
  }
}

TEST(SweptCorridor, NonConvexFootprintLeavesItsNotchUnswept)
{
  // An L: the rear left quarter is cut away (x < 0 and y > 0.1).
  const std::vector<Vec2> l_shape{{0.4, 0.3}, {0.0, 0.3}, {0.0, 0.1}, {-0.2, 0.1}, {-0.2, -0.3}, {0.4, -0.3}};
  ASSERT_EQ("", footprintProblem(l_shape));
  const Path path = straightPath(5.0);
  const SweptCorridor corridor = sweep(path, 1.0, l_shape, 1.0);
  // The robot starts at x = 1: behind it, left of y = 0.1, nothing ever passes.
  EXPECT_FALSE(covered(corridor.band(), {0.9, 0.2}));
  EXPECT_TRUE(covered(corridor.band(), {0.9, 0.0}));
  EXPECT_TRUE(covered(corridor.band(), {1.5, 0.2}));
  EXPECT_TRUE(covered(corridor.band(), {2.39, 0.29}));
  EXPECT_FALSE(covered(corridor.band(), {2.41, 0.0}));
  ASSERT_EQ(2u, corridor.edgeLines().size());
  for (const std::vector<Vec2>& line : corridor.edgeLines())
  {
    for (const Vec2& p : line)
    {
      EXPECT_NEAR(0.3, std::abs(p.y), 1e-4) << p.x << ", " << p.y;
    }
  }
}

TEST(SweptCorridor, ClippedAtTheDestination)
{
  const Path path = straightPath(2.0);
  const SweptCorridor corridor = sweep(path, 1.5, kRectangle, 3.0);
  double farthest = -INFINITY;
  for (const Vec2& p : corridor.band())
  {
    farthest = std::max(farthest, p.x);
  }
  EXPECT_NEAR(2.4, farthest, 1e-4) << "the robot's front at the destination (x = 2), no further";
  const SweptCorridor there = sweep(path, 2.0, kRectangle, 3.0);
  EXPECT_TRUE(there.band().empty()) << "standing at the destination: nothing left to sweep";
  EXPECT_TRUE(there.edges().empty());
}

TEST(SweptCorridor, BadFootprintsAreRefusedWithAReason)
{
  EXPECT_NE(std::string::npos, footprintProblem({}).find("0 points"));
  EXPECT_NE(std::string::npos, footprintProblem({{0, 0}, {1, 0}}).find("2 points"));
  EXPECT_NE(std::string::npos, footprintProblem({{0, 0}, {1, 0}, {NAN, 1}}).find("finite"));
  EXPECT_NE(std::string::npos, footprintProblem({{0, 0}, {1, 0}, {2, 0}}).find("no area"));
  EXPECT_NE(std::string::npos, footprintProblem({{0, 0}, {2, 2}, {2, 0}, {0, 1}}).find("cross"));
  EXPECT_EQ("", footprintProblem(kRectangle));

  const Path path = straightPath(5.0);
  SweptCorridor corridor;
  corridor.build(path.points, path.lengths, 0.0, kRectangle, CorridorParameters());
  ASSERT_FALSE(corridor.band().empty());
  // A bad footprint after a good one: the last corridor does not stay.
  corridor.build(path.points, path.lengths, 0.0, {{0, 0}, {2, 2}, {2, 0}, {0, 1}}, CorridorParameters());
  EXPECT_TRUE(corridor.band().empty());
  EXPECT_TRUE(corridor.edges().empty());
  for (const double radius : {0.0, -1.0, double(NAN), double(INFINITY)})
  {
    corridor.buildRound(path.points, path.lengths, 0.0, radius, CorridorParameters());
    EXPECT_TRUE(corridor.band().empty()) << radius;
  }
}

TEST(SweptCorridor, FootprintsAreReadAsMoveBaseWritesThem)
{
  std::string error;
  const std::vector<Vec2> polygon = parseFootprint("[[0.4, 0.3], [-0.2, 0.3],[-0.2,-0.3], [0.4, -3e-1]]", error);
  EXPECT_EQ("", error);
  ASSERT_EQ(4u, polygon.size());
  EXPECT_DOUBLE_EQ(-0.2, polygon[2].x);
  EXPECT_DOUBLE_EQ(-0.3, polygon[3].y);
  for (const auto& bad : std::vector<std::pair<std::string, std::string>>{
           {"", "no points"},
           {"[[0.4, 0.3], [0.1]]", "point 2 has 1 numbers"},
           {"[[0.4, 0.3, 1], [0.1, 2]]", "point 1 has 3 numbers"},
           {"[[0.4, 0.3], [0.1, 0.2]", "without its ']'"},
           {"[[0.4, 0.3]]]", "without its '['"},
           {"[[[0.4, 0.3]]]", "more than two levels"},
           {"[[0.4, wide]]", "unexpected 'wide]]'"},
           {"0.3", "unexpected '0.3'"}})
  {
    EXPECT_TRUE(parseFootprint(bad.first, error).empty()) << bad.first;
    EXPECT_NE(std::string::npos, error.find(bad.second)) << bad.first << ": " << error;
    EXPECT_NE(std::string::npos, error.find("[[x, y], [x, y], ...]")) << error;
  }
}

TEST(SweptCorridor, ClockwiseFootprintSweepsTheSame)
{
  std::vector<Vec2> clockwise = kRectangle;
  std::reverse(clockwise.begin(), clockwise.end());
  const Path path = straightPath(5.0);
  SweptCorridor a, b;
  a.build(path.points, path.lengths, 1.0, kRectangle, CorridorParameters());
  b.build(path.points, path.lengths, 1.0, clockwise, CorridorParameters());
  ASSERT_EQ(a.edgeLines().size(), b.edgeLines().size());
  for (std::size_t i = 0; i < a.edgeLines().size(); ++i)
  {
    ASSERT_EQ(a.edgeLines()[i].size(), b.edgeLines()[i].size());
    for (std::size_t j = 0; j < a.edgeLines()[i].size(); ++j)
    {
      EXPECT_NEAR(a.edgeLines()[i][j].x, b.edgeLines()[i][j].x, 1e-9);
      EXPECT_NEAR(a.edgeLines()[i][j].y, b.edgeLines()[i][j].y, 1e-9);
    }
  }
}
}  // namespace
}  // namespace rviz_projector
