// The stop zone (issue 25): stopping distance, the speed filter and the zone's triangles against
// values computed by hand (d = v^2 / (2 a) + v t; the low-pass's step response 1 - exp(-t / tau);
// the areas of a rectangle and of an annulus sector).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/cue_drawing.h"
#include "rviz_projector/core/path_location.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/stop_zone.h"

using namespace rviz_projector;

namespace
{
constexpr double kPi = 3.14159265358979323846;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<Vec2> straight(double length, double step = 0.1)
{
  std::vector<Vec2> points;
  for (double x = 0.0; x < length - 1e-9; x += step)
  {
    points.push_back({x, 0.0});
  }
  points.push_back({length, 0.0});
  return points;
}

double triangleArea(const Vec2& a, const Vec2& b, const Vec2& c)
{
  return 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

/// Total area of the triangles whose vertices' alpha factor satisfies `pick`.
template <typename Pick>
double area(const StopZone& zone, Pick pick)
{
  double sum = 0.0;
  const auto& t = zone.triangles();
  for (std::size_t i = 0; i + 2 < t.size(); i += 3)
  {
    if (pick(zone.alpha()[i]))
    {
      sum += triangleArea(t[i], t[i + 1], t[i + 2]);
    }
  }
  return sum;
}

SpeedEstimate moving(double v)
{
  return SpeedEstimate{v, true};
}
}  // namespace

TEST(StoppingDistance, TheFormulaByHand)
{
  EXPECT_DOUBLE_EQ(stoppingDistance(1.0, 0.5, 0.3), 1.0 + 0.3);     // 1 / (2 * 0.5) + 1 * 0.3
  EXPECT_DOUBLE_EQ(stoppingDistance(0.8, 0.5, 0.3), 0.64 + 0.24);   // 0.64 / 1 + 0.8 * 0.3
  EXPECT_DOUBLE_EQ(stoppingDistance(2.0, 1.0, 0.0), 2.0);           // 4 / 2, no reaction
  EXPECT_DOUBLE_EQ(stoppingDistance(0.0, 0.5, 0.3), 0.0);
  EXPECT_DOUBLE_EQ(stoppingDistance(-1.0, 0.5, 0.3), 1.3) << "reverse: the magnitude counts";
}

TEST(StoppingDistance, BadInputIsNaN)
{
  EXPECT_TRUE(std::isnan(stoppingDistance(kNaN, 0.5, 0.3)));
  EXPECT_TRUE(std::isnan(stoppingDistance(std::numeric_limits<double>::infinity(), 0.5, 0.3)));
  EXPECT_TRUE(std::isnan(stoppingDistance(1.0, 0.0, 0.3)));
  EXPECT_TRUE(std::isnan(stoppingDistance(1.0, -1.0, 0.3)));
  EXPECT_TRUE(std::isnan(stoppingDistance(1.0, 0.5, -0.1)));
  EXPECT_TRUE(std::isnan(stoppingDistance(1.0, kNaN, 0.3)));
}

TEST(SpeedFilter, StepResponseIsFirstOrderWithTheDocumentedTimeConstant)
{
  SpeedFilter f;
  EXPECT_FALSE(f.at(0.0).moving) << "no measurement: standing";
  f.add(0.0, 10.0);
  f.add(1.0, 11.0);  // a step from 0 to 1 m/s at t = 11
  const double tau = 0.3;
  for (double t : {0.0, 0.1, 0.3, 0.6, 1.0, 2.0})
  {
    EXPECT_NEAR(f.at(11.0 + t).speed, 1.0 - std::exp(-t / tau), 1e-12) << "t = " << t;
  }
  // Reading it often or seldom, and repeating the same measurement, changes nothing.
  SpeedFilter g;
  g.add(0.0, 10.0);
  for (double t = 11.0; t < 11.6 - 1e-9; t += 0.01)
  {
    g.add(1.0, t);
    g.at(t + 0.005);
  }
  EXPECT_NEAR(g.at(11.6).speed, 1.0 - std::exp(-0.6 / tau), 1e-12);
}

TEST(SpeedFilter, FirstMeasurementIsTakenAsItIs)
{
  SpeedFilter f;
  f.add(-0.7, 3.0);  // reversing: the magnitude
  EXPECT_DOUBLE_EQ(f.at(3.0).speed, 0.7);
  EXPECT_TRUE(f.at(3.0).moving);
}

TEST(SpeedFilter, NoiseBarelyMovesTheOutput)
{
  SpeedFilter f;
  // 0.5 m/s with +-0.05 m/s noise at 50 Hz for 3 s.
  double t = 0.0;
  double lowest = 1e9, highest = -1e9;
  for (int i = 0; i < 150; ++i, t += 0.02)
  {
    f.add(i % 2 == 0 ? 0.55 : 0.45, t);
    if (t > 1.0)
    {
      const double v = f.at(t + 0.01).speed;
      lowest = std::min(lowest, v);
      highest = std::max(highest, v);
    }
  }
  // Ripple of a first-order low-pass with tau = 0.3 s at this rate: about 0.05 * 0.02 / 0.3 / 2 ~ 0.002.
  EXPECT_LT(highest - lowest, 0.005);
  EXPECT_NEAR(0.5 * (highest + lowest), 0.5, 0.005);
}

TEST(SpeedFilter, StandingHasHysteresis)
{
  SpeedFilter f;
  f.add(0.5, 0.0);
  ASSERT_TRUE(f.at(0.0).moving);
  f.add(0.025, 0.0);  // slow, but above the standing threshold: still moving when settled
  EXPECT_TRUE(f.at(5.0).moving);
  f.add(0.0, 5.0);
  // 0.025 exp(-t / 0.3) < 0.02 after t = 0.3 ln(1.25) = 0.067 s.
  EXPECT_TRUE(f.at(5.05).moving);
  EXPECT_FALSE(f.at(5.1).moving);
  f.add(0.025, 6.0);  // below the moving threshold: stays standing
  EXPECT_FALSE(f.at(9.0).moving);
  f.add(0.05, 9.0);  // 0.05 - 0.025 exp(-t / 0.3) > 0.03 after t = 0.3 ln(1.25) = 0.067 s
  EXPECT_FALSE(f.at(9.05).moving);
  EXPECT_TRUE(f.at(9.1).moving);
}

TEST(SpeedFilter, TimeGoingBackStartsAfreshAndNaNIsIgnored)
{
  SpeedFilter f;
  f.add(1.0, 100.0);
  f.add(kNaN, 101.0);
  EXPECT_DOUBLE_EQ(f.at(102.0).speed, 1.0);
  f.add(0.2, 50.0);  // a bag loop
  EXPECT_DOUBLE_EQ(f.at(50.0).speed, 0.2);
  f.clear();
  EXPECT_TRUE(f.empty());
  EXPECT_FALSE(f.at(50.0).moving);
}

TEST(StopZone, BarEndsAtTheStoppingPointOnAStraightPath)
{
  const std::vector<Vec2> path = straight(5.0);
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  StopZoneParameters p;  // a = 0.5, t = 0.3, width 0.3, filled, alpha 0.4
  StopZone zone;
  zone.build(path, lengths, 0.5, moving(1.0), p);
  ASSERT_TRUE(zone.shown());
  EXPECT_DOUBLE_EQ(zone.start(), 0.5);
  EXPECT_NEAR(zone.end(), 0.5 + 1.3, 1e-12);
  double min_x = 1e9, max_x = -1e9, max_y = 0.0;
  for (std::size_t i = 0; i < zone.triangles().size(); ++i)
  {
    const Vec2& v = zone.triangles()[i];
    min_x = std::min(min_x, v.x);
    max_x = std::max(max_x, v.x);
    max_y = std::max(max_y, std::abs(v.y));
    if (zone.alpha()[i] == 1.0f)
    {
      EXPECT_GE(v.x, 1.8 - 0.05 - 1e-9) << "the bar is the last 5 cm";
    }
    else
    {
      EXPECT_FLOAT_EQ(zone.alpha()[i], 0.4f);
      EXPECT_LE(v.x, 1.75 + 1e-9);
    }
  }
  EXPECT_NEAR(min_x, 0.5, 1e-9);
  EXPECT_NEAR(max_x, 1.8, 1e-9);
  EXPECT_NEAR(max_y, 0.15, 1e-9);
  EXPECT_NEAR(area(zone, [](float a) { return a == 1.0f; }), 0.05 * 0.3, 1e-9) << "bar";
  EXPECT_NEAR(area(zone, [](float a) { return a < 1.0f; }), (1.3 - 0.05) * 0.3, 1e-9) << "fill";
}

TEST(StopZone, HatchedDrawsStripesFromTheRobot)
{
  const std::vector<Vec2> path = straight(5.0);
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  StopZoneParameters p;
  p.hatched = true;
  p.width = 0.2;
  StopZone zone;
  zone.build(path, lengths, 0.0, moving(1.0), p);  // end 1.3, bar from 1.25
  // Stripes [0, 0.05], [0.15, 0.2], ..., [1.2, 1.25]: 9 of 5 cm.
  EXPECT_NEAR(area(zone, [](float a) { return a < 1.0f; }), 9 * 0.05 * 0.2, 1e-9);
  for (std::size_t i = 0; i < zone.triangles().size(); ++i)
  {
    const double x = zone.triangles()[i].x;
    if (zone.alpha()[i] < 1.0f)
    {
      const double within = std::fmod(x + 1e-9, 0.15);
      EXPECT_LE(within, 0.05 + 2e-9) << "a stripe vertex between stripes at x = " << x;
    }
  }
}

TEST(StopZone, NeverBeyondTheDestination)
{
  const std::vector<Vec2> path = straight(2.0);
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  StopZone zone;
  zone.build(path, lengths, 0.5, moving(2.0), StopZoneParameters());  // d = 4 + 0.6 = 4.6
  ASSERT_TRUE(zone.shown());
  EXPECT_DOUBLE_EQ(zone.end(), 2.0);
  double max_x = -1e9;
  for (const Vec2& v : zone.triangles())
  {
    max_x = std::max(max_x, v.x);
  }
  EXPECT_NEAR(max_x, 2.0, 1e-9);
  zone.build(path, lengths, 2.0, moving(1.0), StopZoneParameters());
  EXPECT_FALSE(zone.shown()) << "at the destination: nothing ahead";
}

TEST(StopZone, HiddenWhileStandingOrOnBadInput)
{
  const std::vector<Vec2> path = straight(5.0);
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  StopZone zone;
  zone.build(path, lengths, 0.5, SpeedEstimate{1.0, false}, StopZoneParameters());
  EXPECT_FALSE(zone.shown()) << "standing";
  zone.build(path, lengths, 0.5, moving(kNaN), StopZoneParameters());
  EXPECT_FALSE(zone.shown());
  zone.build(path, lengths, kNaN, moving(1.0), StopZoneParameters());
  EXPECT_FALSE(zone.shown());
  StopZoneParameters bad;
  bad.deceleration = 0.0;
  zone.build(path, lengths, 0.5, moving(1.0), bad);
  EXPECT_FALSE(zone.shown());
  zone.build({Vec2{1, 1}}, {0.0}, 0.0, moving(1.0), StopZoneParameters());
  EXPECT_FALSE(zone.shown()) << "one-point path";
  zone.build({}, {}, 0.0, moving(1.0), StopZoneParameters());
  EXPECT_FALSE(zone.shown());
}

TEST(StopZone, FollowsACurvedPath)
{
  // A quarter circle of radius 2 about the origin from (2, 0) to (0, 2), 1 degree per point.
  std::vector<Vec2> path;
  for (int k = 0; k <= 90; ++k)
  {
    const double a = k * kPi / 180.0;
    path.push_back({2.0 * std::cos(a), 2.0 * std::sin(a)});
  }
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  StopZoneParameters p;
  p.width = 0.4;
  StopZone zone;
  zone.build(path, lengths, 0.0, moving(1.0), p);  // d = 1.3 m of path
  ASSERT_TRUE(zone.shown());
  // Every vertex lies between the radii 1.8 and 2.2 (the polyline's mitres: within 1e-3).
  for (const Vec2& v : zone.triangles())
  {
    const double r = norm(v);
    EXPECT_TRUE(std::abs(r - 1.8) < 1e-3 || std::abs(r - 2.2) < 1e-3) << "r = " << r;
  }
  // Area of the annulus sector under the path's 1.3 m (radius 2): width x arc length.
  EXPECT_NEAR(area(zone, [](float) { return true; }), 0.4 * 1.3, 2e-3);
  // The bar sits across the path at 1.3 m of arc: its vertices' angles are within [1.25, 1.3] / 2 rad.
  for (std::size_t i = 0; i < zone.triangles().size(); ++i)
  {
    if (zone.alpha()[i] == 1.0f)
    {
      const double angle = std::atan2(zone.triangles()[i].y, zone.triangles()[i].x);
      EXPECT_GE(angle, 1.25 / 2.0 - 1e-3);
      EXPECT_LE(angle, 1.3 / 2.0 + 1e-3);
    }
  }
}

TEST(StopZone, MitredCornersKeepTheWidth)
{
  // An L: 1 m along +x, then 1 m along +y; the zone from arc 0.5 to 1.5 turns the corner. A strip
  // with mitred joints has exactly the area width x centre-line length; the outer corner vertex lies
  // at (1 + w/2, -w/2).
  const std::vector<Vec2> path = {Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}};
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  std::vector<Vec2> band;
  appendPathBand(path, lengths, 0.5, 1.5, 0.3, band);
  double sum = 0.0;
  bool outer_corner = false;
  for (std::size_t i = 0; i + 2 < band.size(); i += 3)
  {
    sum += triangleArea(band[i], band[i + 1], band[i + 2]);
  }
  for (const Vec2& v : band)
  {
    outer_corner = outer_corner || (std::abs(v.x - 1.15) < 1e-12 && std::abs(v.y + 0.15) < 1e-12);
  }
  EXPECT_NEAR(sum, 0.3 * 1.0, 1e-12);
  EXPECT_TRUE(outer_corner);
}

TEST(StopZone, CueDrawingDrawsItOnlyWithTheArrowsAndFromTheRobot)
{
  const std::vector<Vec2> path = straight(5.0);
  SpacingParameters parameters;
  PathSpacer spacer(parameters);
  PathCueSettings settings;
  settings.stop_zone = true;
  PathCueInput input;
  input.robot_known = true;
  input.robot = {1.0, 0.2};  // beside the path at x 1: arc 1
  input.speed = moving(1.0);
  CueDrawing d;
  d.build(path, spacer.space(path), parameters, settings, input);
  ASSERT_TRUE(d.stopZone().shown());
  EXPECT_NEAR(d.stopZone().start(), 1.0, 1e-12);
  EXPECT_NEAR(d.stopZone().end(), 2.3, 1e-12);
  input.goal.arrows = false;  // a failed goal hides the arrows: the path is no promise, no zone either
  d.build(path, spacer.space(path), parameters, settings, input);
  EXPECT_FALSE(d.stopZone().shown());
  input.goal.arrows = true;
  settings.stop_zone = false;
  d.build(path, spacer.space(path), parameters, settings, input);
  EXPECT_FALSE(d.stopZone().shown()) << "off by default";
}

TEST(StopZone, HatchingIsBoundedOnAHugeZone)
{
  // 10 km of path and a bogus 200 m/s: d = 40,000 + 60 m, clipped at 10 km. 2000 stripes (300 m),
  // then the rest filled: fill area 0.3 x (2000 x 0.05 + (10,000 - 0.05 - 300)) m^2.
  const std::vector<Vec2> path = straight(10000.0, 10.0);
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  StopZoneParameters p;
  p.hatched = true;
  StopZone zone;
  zone.build(path, lengths, 0.0, moving(200.0), p);
  ASSERT_TRUE(zone.shown());
  EXPECT_NEAR(area(zone, [](float a) { return a < 1.0f; }), 0.3 * (2000 * 0.05 + (10000.0 - 0.05 - 300.0)), 1e-6);
  EXPECT_LT(zone.triangles().size(), 2u * 3u * (2000u + 1000u + 10u));
}
