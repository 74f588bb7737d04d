// Paper mode of PathSpacer: Algorithm 1 of Han et al. (HRI 2022) as the reference code runs it.
// Coordinates are multiples of 1/16 so distances compare exactly against the thresholds.
#include <gtest/gtest.h>

#include <vector>

#include "rviz_projector/core/path_spacer.h"

using rviz_projector::PathSpacer;
using rviz_projector::SpacedPath;
using rviz_projector::SpacingMode;
using rviz_projector::SpacingParameters;
using rviz_projector::Vec2;

namespace
{
SpacingParameters paperParameters()
{
  SpacingParameters p;
  p.mode = SpacingMode::Paper;
  p.spacing = 0.125;         // D
  p.circle_diameter = 0.125;  // destination needs D + diameter = 0.25
  return p;
}

std::vector<Vec2> xs(const std::vector<double>& values)
{
  std::vector<Vec2> path;
  for (double x : values)
  {
    path.push_back({x, 0.0});
  }
  return path;
}
}  // namespace

TEST(PathSpacerPaper, EvenLineKeepsEveryOtherPairAfterTheDestinationRule)
{
  std::vector<double> values;
  for (int i = 0; i <= 16; ++i)
  {
    values.push_back(0.0625 * i);
  }
  PathSpacer spacer(paperParameters());
  const SpacedPath& out = spacer.space(xs(values));
  // Kept: 1.0 (destination), 0.75 (first at >= 0.25), then every 0.125: 0.625, 0.5, 0.375, 0.25,
  // 0.125; the walk reaches index 0 (x = 0) and stops without keeping it, as the reference does.
  // Arrows join pairs: 0.75 -> 1.0, 0.5 -> 0.625, 0.25 -> 0.375.
  ASSERT_EQ(out.arrows.size(), 3u);
  const double tails[] = {0.75, 0.5, 0.25};
  const double tips[] = {1.0, 0.625, 0.375};
  for (std::size_t k = 0; k < 3; ++k)
  {
    EXPECT_DOUBLE_EQ(out.arrows[k].tail.x, tails[k]) << k;
    EXPECT_DOUBLE_EQ(out.arrows[k].tip.x, tips[k]) << k;
  }
  EXPECT_DOUBLE_EQ(out.destination.x, 1.0);
}

TEST(PathSpacerPaper, UnevenPosesFollowTheWalk)
{
  PathSpacer spacer(paperParameters());
  // Destination 1.0; 0.9 is 0.1 < 0.25 away, 0.5 is kept; 0.35 is 0.15 >= 0.125 away, kept;
  // 0.3 is too close, 0.0 is index 0: the walk ends. Kept 1.0, 0.5, 0.35 -> one arrow 0.5 -> 1.0.
  const SpacedPath& out = spacer.space(xs({0.0, 0.3, 0.35, 0.5, 0.9, 1.0}));
  ASSERT_EQ(out.arrows.size(), 1u);
  EXPECT_DOUBLE_EQ(out.arrows[0].tail.x, 0.5);
  EXPECT_DOUBLE_EQ(out.arrows[0].tip.x, 1.0);
}

TEST(PathSpacerPaper, DestinationRuleUsesSpacingPlusDiameter)
{
  SpacingParameters p = paperParameters();
  PathSpacer spacer(p);
  // 0.8125 is 0.1875 from the destination: enough for D but not for D + diameter.
  const SpacedPath& narrow = spacer.space(xs({0.0, 0.25, 0.5625, 0.8125, 1.0}));
  // Kept: 1.0, 0.5625 (0.4375 away), 0.25 (0.3125 away); index 0 ends the walk. One arrow.
  ASSERT_EQ(narrow.arrows.size(), 1u);
  EXPECT_DOUBLE_EQ(narrow.arrows[0].tail.x, 0.5625);

  p.circle_diameter = 0.0;  // now 0.8125 qualifies
  spacer.setParameters(p);
  // Kept: 1.0, 0.8125, 0.5625, 0.25 -> two arrows.
  const SpacedPath& wide = spacer.space(xs({0.0, 0.25, 0.5625, 0.8125, 1.0}));
  ASSERT_EQ(wide.arrows.size(), 2u);
  EXPECT_DOUBLE_EQ(wide.arrows[0].tail.x, 0.8125);
  EXPECT_DOUBLE_EQ(wide.arrows[0].tip.x, 1.0);
}

TEST(PathSpacerPaper, DistanceIsPlanar)
{
  PathSpacer spacer(paperParameters());
  // (0.9375, 0) is 0.0625 from (1, 0); (0.75, 0.25) is sqrt(0.125) = 0.354: kept. Then (0.625, 0.25)
  // and (0.5, 0.25) are each 0.125 on: kept; index 0 ends the walk. Four kept -> two arrows.
  const SpacedPath& out =
      spacer.space({{0.0, 0.0}, {0.5, 0.25}, {0.625, 0.25}, {0.75, 0.25}, {0.9375, 0.0}, {1.0, 0.0}});
  ASSERT_EQ(out.arrows.size(), 2u);
  EXPECT_DOUBLE_EQ(out.arrows[0].tail.x, 0.75);
  EXPECT_DOUBLE_EQ(out.arrows[0].tail.y, 0.25);
  EXPECT_DOUBLE_EQ(out.arrows[0].tip.x, 1.0);
  EXPECT_DOUBLE_EQ(out.arrows[1].tail.x, 0.5);
  EXPECT_DOUBLE_EQ(out.arrows[1].tip.x, 0.625);
}

TEST(PathSpacerPaper, PathsShorterThanOneSpacingHaveNoArrows)
{
  PathSpacer spacer(paperParameters());
  const SpacedPath& short_path = spacer.space(xs({0.0, 0.0625, 0.125}));
  EXPECT_TRUE(short_path.has_destination);
  EXPECT_DOUBLE_EQ(short_path.destination.x, 0.125);
  EXPECT_TRUE(short_path.arrows.empty());

  EXPECT_TRUE(spacer.space(xs({2.0})).arrows.empty());
  EXPECT_TRUE(spacer.space({}).arrows.empty());
  EXPECT_FALSE(spacer.space({}).has_destination);
  // Two poses far apart: the walk reaches index 0, which is never kept: no pair, no arrow.
  EXPECT_TRUE(spacer.space(xs({0.0, 5.0})).arrows.empty());
  // Identical poses never reach the distance.
  EXPECT_TRUE(spacer.space(std::vector<Vec2>(1000, Vec2{1.0, 1.0})).arrows.empty());
}

TEST(PathSpacerPaper, ArrowsUseTheKeptPointsWhateverTheShaftLength)
{
  SpacingParameters p = paperParameters();
  p.arrow.shaft_length = 5.0;  // ignored in Paper mode: the kept points decide
  PathSpacer spacer(p);
  const SpacedPath& out = spacer.space(xs({0.0, 0.3, 0.35, 0.5, 0.9, 1.0}));
  ASSERT_EQ(out.arrows.size(), 1u);
  EXPECT_DOUBLE_EQ(out.arrows[0].tail.x, 0.5);
}

TEST(PathSpacerPaper, MillionPosesRunInLinearTime)
{
  std::vector<Vec2> path(1000000);
  for (std::size_t i = 0; i < path.size(); ++i)
  {
    path[i] = {0.0625 * static_cast<double>(i), 0.0};
  }
  SpacingParameters p = paperParameters();
  p.max_arrows = 1000000;
  PathSpacer spacer(p);
  const SpacedPath& out = spacer.space(path);
  // Kept: N-1 (destination), N-5 (first >= 0.25 away), then every 2nd pose down to index 1:
  // 1 + (N-5-1)/2 + 1 points, paired into arrows.
  const std::size_t kept = (1000000 - 5 - 1) / 2 + 2;
  EXPECT_EQ(out.arrows.size(), kept / 2);
  EXPECT_FALSE(out.truncated);

  spacer.setParameters(paperParameters());  // default cap of 100000 arrows
  const SpacedPath& capped = spacer.space(path);
  EXPECT_EQ(capped.arrows.size(), SpacingParameters().max_arrows);
  EXPECT_TRUE(capped.truncated);
}
