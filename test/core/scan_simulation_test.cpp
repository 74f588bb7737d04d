// simulateScan (the demo pedestrian's laser): ranges against hand-computed ray-circle distances.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/scan_simulation.h"

using rviz_projector::Circle;
using rviz_projector::ScanGeometry;
using rviz_projector::simulateScan;
using rviz_projector::Vec2;

namespace
{
constexpr double kPi = 3.14159265358979323846;

/// Four beams: -90, 0, +90 and +180 degrees.
ScanGeometry fourBeams()
{
  ScanGeometry g;
  g.angle_min = -kPi / 2;
  g.angle_increment = kPi / 2;
  g.beams = 4;
  g.range_min = 0.05;
  g.range_max = 10.0;
  return g;
}
}  // namespace

TEST(ScanSimulation, CircleStraightAheadIsAtCentreMinusRadius)
{
  std::vector<float> ranges;
  simulateScan(fourBeams(), Vec2{0, 0}, 0.0, {Circle{Vec2{2.0, 0.0}, 0.5}}, ranges);
  ASSERT_EQ(ranges.size(), 4u);
  EXPECT_TRUE(std::isinf(ranges[0]));       // -90 degrees: nothing
  EXPECT_NEAR(ranges[1], 1.5, 1e-6);        // straight ahead: 2 - 0.5
  EXPECT_TRUE(std::isinf(ranges[2]));       // +90
  EXPECT_TRUE(std::isinf(ranges[3]));       // behind: the circle is ahead
}

TEST(ScanSimulation, OffAxisBeamHitsTheChord)
{
  // Beam along +y from (1, 0) to a circle at (1.3, 2) radius 0.5: x offset 0.3, so the hit is at
  // y = 2 - sqrt(0.25 - 0.09) = 1.6.
  ScanGeometry g = fourBeams();
  std::vector<float> ranges;
  simulateScan(g, Vec2{1.0, 0.0}, 0.0, {Circle{Vec2{1.3, 2.0}, 0.5}}, ranges);
  EXPECT_NEAR(ranges[2], 1.6, 1e-6);
}

TEST(ScanSimulation, YawTurnsTheBeamsAndNearestCircleWins)
{
  std::vector<float> ranges;
  // Heading +y: beam 1 (0 degrees) points along +y; two circles on it, the nearer one counts.
  simulateScan(fourBeams(), Vec2{0, 0}, kPi / 2, {Circle{Vec2{0, 5.0}, 0.5}, Circle{Vec2{0, 3.0}, 0.25}}, ranges);
  EXPECT_NEAR(ranges[1], 2.75, 1e-6);
  // Beam 0 (-90 degrees from +y) points along +x: nothing there.
  EXPECT_TRUE(std::isinf(ranges[0]));
}

TEST(ScanSimulation, BeyondRangeMaxIsNoReturnAndInsideIsRangeMin)
{
  ScanGeometry g = fourBeams();
  g.range_max = 1.0;
  std::vector<float> ranges;
  simulateScan(g, Vec2{0, 0}, 0.0, {Circle{Vec2{2.0, 0.0}, 0.5}}, ranges);
  EXPECT_TRUE(std::isinf(ranges[1]));
  simulateScan(fourBeams(), Vec2{0, 0}, 0.0, {Circle{Vec2{0.1, 0.0}, 0.5}}, ranges);
  for (float r : ranges)
  {
    EXPECT_FLOAT_EQ(r, 0.05f);
  }
}

TEST(ScanSimulation, BadInputGivesNoReturns)
{
  std::vector<float> ranges;
  simulateScan(fourBeams(), Vec2{std::nan(""), 0}, 0.0, {Circle{Vec2{2.0, 0.0}, 0.5}}, ranges);
  ASSERT_EQ(ranges.size(), 4u);
  for (float r : ranges)
  {
    EXPECT_TRUE(std::isinf(r));
  }
  simulateScan(fourBeams(), Vec2{0, 0}, 0.0, {Circle{Vec2{2.0, 0.0}, -1.0}, Circle{Vec2{INFINITY, 0}, 1.0}}, ranges);
  EXPECT_TRUE(std::isinf(ranges[1]));
  ScanGeometry none = fourBeams();
  none.beams = -3;
  simulateScan(none, Vec2{0, 0}, 0.0, {}, ranges);
  EXPECT_TRUE(ranges.empty());
}

TEST(ScanSimulation, DefaultGeometryHasItsMiddleBeamStraightAhead)
{
  const ScanGeometry g;
  std::vector<float> ranges;
  simulateScan(g, Vec2{0, 0}, 0.0, {Circle{Vec2{3.0, 0.0}, 0.2}}, ranges);
  ASSERT_EQ(ranges.size(), 1081u);
  EXPECT_NEAR(ranges[540], 2.8, 1e-5);
  // The circle subtends asin(0.2 / 3) = 3.82 degrees each side: about 15 beams each side see it.
  int seen = 0;
  for (float r : ranges)
  {
    seen += std::isfinite(r) ? 1 : 0;
  }
  const int expected = 2 * static_cast<int>(std::asin(0.2 / 3.0) / g.angle_increment) + 1;
  EXPECT_NEAR(seen, expected, 2);
}
