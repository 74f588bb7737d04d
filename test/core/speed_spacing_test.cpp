// Speed-coded spacing (Stop zone > Speed-coded spacing, issue 25 part 2): arrow tips on a straight
// path, their distances from the destination checked against the braking formula computed here by
// hand (v = min(v0, sqrt(2 a d)), spacing = max(min, v T)).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/speed_spacing.h"

using namespace rviz_projector;

namespace
{
const double kNan = std::numeric_limits<double>::quiet_NaN();

/// A straight 10 m path along +x ending at (10, 0), sampled every 5 cm.
std::vector<Vec2> straight()
{
  std::vector<Vec2> points;
  for (int i = 0; i <= 200; ++i)
  {
    points.push_back({0.05 * i, 0.0});
  }
  return points;
}

SpacingParameters coded(double speed, double deceleration, double time_step, double min_spacing)
{
  SpacingParameters p;
  p.circle_diameter = 0.2;  // first tip 0.1 + 0.05 from the destination
  p.destination_gap = 0.05;
  p.speed_coding.enabled = true;
  p.speed_coding.speed = speed;
  p.speed_coding.deceleration = deceleration;
  p.speed_coding.time_step = time_step;
  p.speed_coding.min_spacing = min_spacing;
  return p;
}

/// Distances of the tips from the destination (10, 0), from the arrows' tips themselves.
std::vector<double> tipDistances(const SpacedPath& spaced)
{
  std::vector<double> out;
  for (const Arrow& arrow : spaced.arrows)
  {
    EXPECT_NEAR(arrow.tip.y, 0.0, 1e-12);
    out.push_back(10.0 - arrow.tip.x);
  }
  return out;
}
}  // namespace

TEST(SpeedSpacing, CruisingRobotBrakesForItsDestination)
{
  // v0 = 0.4 m/s, a = 0.5 m/s^2, T = 0.5 s: the braking curve reaches 0.4 m/s at d = 0.16 m.
  PathSpacer spacer(coded(0.4, 0.5, 0.5, 0.1));
  const std::vector<double> d = tipDistances(spacer.space(straight()));
  ASSERT_GT(d.size(), 10u);
  EXPECT_NEAR(d[0], 0.15, 1e-9);
  // d = 0.15 < 0.16: still braking there, v = sqrt(2 * 0.5 * 0.15) = 0.387298 m/s -> 0.193649 m.
  EXPECT_NEAR(d[1], 0.15 + 0.193649, 1e-6);
  // From then on at cruise: 0.4 * 0.5 = 0.2 m apart.
  for (std::size_t k = 2; k < d.size(); ++k)
  {
    EXPECT_NEAR(d[k] - d[k - 1], 0.2, 1e-9) << k;
  }
}

TEST(SpeedSpacing, ArrowsCrowdWhereTheRobotSlowsDown)
{
  // Gentle braking (a = 0.05): v = sqrt(0.1 d) until 0.4 m/s at d = 1.6 m.
  PathSpacer spacer(coded(0.4, 0.05, 0.5, 0.1));
  const std::vector<double> d = tipDistances(spacer.space(straight()));
  ASSERT_GT(d.size(), 10u);
  double previous_gap = 0.0;
  for (std::size_t k = 1; k < d.size(); ++k)
  {
    const double v = std::min(0.4, std::sqrt(0.1 * d[k - 1]));
    const double expected = std::max(0.1, 0.5 * v);
    EXPECT_NEAR(d[k] - d[k - 1], expected, 1e-9) << k;
    EXPECT_GE(d[k] - d[k - 1], previous_gap - 1e-12) << "gaps grow away from the destination";
    previous_gap = d[k] - d[k - 1];
  }
  EXPECT_NEAR(d[1] - d[0], 0.1, 1e-9) << "the minimum spacing near the destination";
  EXPECT_NEAR(d.back() - d[d.size() - 2], 0.2, 1e-9) << "cruise spacing far from it";
}

TEST(SpeedSpacing, StandingRobotGetsTheMinimumSpacingAndNonsenseIsSanitised)
{
  for (double speed : {0.0, -1.0, kNan})
  {
    PathSpacer spacer(coded(speed, 0.5, 0.5, 0.12));
    const std::vector<double> d = tipDistances(spacer.space(straight()));
    ASSERT_GT(d.size(), 3u);
    for (std::size_t k = 1; k < d.size(); ++k)
    {
      EXPECT_NEAR(d[k] - d[k - 1], 0.12, 1e-9) << speed;
    }
  }
  SpeedCoding bad;
  bad.speed = 1.0;
  bad.deceleration = kNan;  // -> 0.5
  bad.time_step = -3.0;     // -> 0.5
  bad.min_spacing = 0.0;    // -> path_style::kMinSpacing
  EXPECT_NEAR(plannedSpeed(bad, 0.25), std::sqrt(0.25), 1e-12);
  EXPECT_NEAR(speedCodedSpacing(bad, 0.25), 0.25, 1e-12);
  EXPECT_NEAR(speedCodedSpacing(bad, 0.0), 0.01, 1e-12);
  EXPECT_EQ(plannedSpeed(bad, kNan), 0.0);
  bad.time_step = 1e300;
  EXPECT_EQ(speedCodedSpacing(bad, 10.0), 100.0) << "capped at the largest spacing";
}

TEST(SpeedSpacing, MarchingPhaseIsNotAppliedAndTheCountIsCapped)
{
  SpacingParameters p = coded(0.4, 0.5, 0.5, 0.1);
  PathSpacer spacer(p);
  const std::vector<double> still = tipDistances(spacer.space(straight(), 0.0));
  const std::vector<double> phased = tipDistances(spacer.space(straight(), 0.13));
  EXPECT_EQ(still, phased);
  p.max_arrows = 5;
  spacer.setParameters(p);
  const SpacedPath& capped = spacer.space(straight());
  EXPECT_EQ(capped.arrows.size(), 5u);
  EXPECT_TRUE(capped.truncated);
}

TEST(SpeedSpacing, OffLeavesTheConstantSpacing)
{
  SpacingParameters p = coded(0.4, 0.05, 0.5, 0.1);
  p.speed_coding.enabled = false;
  p.spacing = 0.3;
  PathSpacer spacer(p);
  const std::vector<double> d = tipDistances(spacer.space(straight()));
  for (std::size_t k = 1; k < d.size(); ++k)
  {
    EXPECT_NEAR(d[k] - d[k - 1], 0.3, 1e-9);
  }
}
