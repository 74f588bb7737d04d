// The path cues' geometry (path_location, path_horizon, marching, PathSpacer's phase) against
// hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/marching.h"
#include "rviz_projector/core/path_horizon.h"
#include "rviz_projector/core/path_location.h"
#include "rviz_projector/core/path_spacer.h"

using namespace rviz_projector;

namespace
{
constexpr double kPi = 3.14159265358979323846;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<Vec2> lPath()  // (0,0) -> (2,0) -> (2,1)
{
  return {Vec2{0, 0}, Vec2{2, 0}, Vec2{2, 1}};
}
}  // namespace

TEST(PathLocation, ArcLengthsAccumulate)
{
  std::vector<double> lengths;
  accumulateArcLengths({Vec2{0, 0}, Vec2{3, 4}, Vec2{3, 5}}, lengths);
  ASSERT_EQ(lengths.size(), 3u);
  EXPECT_DOUBLE_EQ(lengths[0], 0.0);
  EXPECT_DOUBLE_EQ(lengths[1], 5.0);
  EXPECT_DOUBLE_EQ(lengths[2], 6.0);
  accumulateArcLengths({}, lengths);
  EXPECT_TRUE(lengths.empty());
}

TEST(PathLocation, NearestPointOnAStraightLineAndAnL)
{
  const auto path = lPath();
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  PathLocation at = locateOnPath(path, lengths, Vec2{0.7, -0.4});
  ASSERT_TRUE(at.valid);
  EXPECT_NEAR(at.arc_length, 0.7, 1e-12);
  EXPECT_NEAR(at.distance, 0.4, 1e-12);
  // Beside the second leg: (2.5, 0.6) -> (2, 0.6), arc length 2 + 0.6.
  at = locateOnPath(path, lengths, Vec2{2.5, 0.6});
  EXPECT_NEAR(at.arc_length, 2.6, 1e-12);
  EXPECT_NEAR(at.point.y, 0.6, 1e-12);
  // Beyond the start: clamped to the first point.
  at = locateOnPath(path, lengths, Vec2{-3, 0});
  EXPECT_DOUBLE_EQ(at.arc_length, 0.0);
  EXPECT_DOUBLE_EQ(at.distance, 3.0);
}

TEST(PathLocation, ACrossingGoesToTheEarlierPart)
{
  // (0,0) -> (2,0) -> (2,1) -> (1,1) -> (1,-1): crosses itself at (1, 0), arc lengths 1 and 5.
  const std::vector<Vec2> path{Vec2{0, 0}, Vec2{2, 0}, Vec2{2, 1}, Vec2{1, 1}, Vec2{1, -1}};
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  const PathLocation at = locateOnPath(path, lengths, Vec2{1, 0});
  EXPECT_NEAR(at.arc_length, 1.0, 1e-12);
  EXPECT_NEAR(at.distance, 0.0, 1e-12);
}

TEST(PathLocation, BadInput)
{
  std::vector<double> lengths;
  EXPECT_FALSE(locateOnPath({}, lengths, Vec2{0, 0}).valid);
  const auto path = lPath();
  accumulateArcLengths(path, lengths);
  EXPECT_FALSE(locateOnPath(path, lengths, Vec2{kNaN, 0}).valid);
  const PathLocation single = locateOnPath({Vec2{1, 1}}, {0.0}, Vec2{4, 5});
  EXPECT_TRUE(single.valid);
  EXPECT_DOUBLE_EQ(single.distance, 5.0);
}

TEST(PathLocation, PointsAndHeadings)
{
  const auto path = lPath();
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  EXPECT_NEAR(pointAtArcLength(path, lengths, 2.5).y, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(pointAtArcLength(path, lengths, -1).x, 0.0);
  EXPECT_DOUBLE_EQ(pointAtArcLength(path, lengths, 99).y, 1.0);
  EXPECT_NEAR(headingAt(path, lengths, 0.5, 0.2), 0.0, 1e-12);
  EXPECT_NEAR(headingAt(path, lengths, 2.3, 0.2), kPi / 2, 1e-12);
  // Across the corner: chord (1.9, 0) -> (2, 0.1): 45 degrees.
  EXPECT_NEAR(headingAt(path, lengths, 1.9, 0.2), kPi / 4, 1e-12);
  // Near the end: the last chord, (2, 0.8) -> (2, 1).
  EXPECT_NEAR(headingAt(path, lengths, 2.95, 0.2), kPi / 2, 1e-12);
  EXPECT_TRUE(std::isnan(headingAt({Vec2{1, 1}, Vec2{1, 1}}, {0.0, 0.0}, 0.0, 0.2)));
}

TEST(PathHorizon, CutAndLinearFadeByArcLength)
{
  const HorizonWindow w = makeHorizon(1.0, 3.0, 1.0);  // [1, 4], fade from 3
  EXPECT_DOUBLE_EQ(w.alpha(0.99), 0.0);
  EXPECT_DOUBLE_EQ(w.alpha(1.0), 1.0);
  EXPECT_DOUBLE_EQ(w.alpha(3.0), 1.0);
  EXPECT_NEAR(w.alpha(3.25), 0.75, 1e-12);
  EXPECT_NEAR(w.alpha(3.9), 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(w.alpha(4.0), 0.0);
  EXPECT_DOUBLE_EQ(w.alpha(kNaN), 0.0);
  EXPECT_DOUBLE_EQ(HorizonWindow().alpha(123.0), 1.0);  // disabled
}

TEST(PathHorizon, FadeLongerThanTheHorizonAndBadLengths)
{
  const HorizonWindow w = makeHorizon(0.0, 0.5, 2.0);  // the fade is cut to the horizon: 0.5
  EXPECT_NEAR(w.alpha(0.0), 1.0, 1e-12);
  EXPECT_NEAR(w.alpha(0.25), 0.5, 1e-12);
  const HorizonWindow none = makeHorizon(kNaN, -1.0, kNaN);  // start 0, length 0: nothing
  EXPECT_DOUBLE_EQ(none.alpha(0.0), 0.0);
  EXPECT_DOUBLE_EQ(none.alpha(1.0), 0.0);
}

TEST(Marching, PhaseShrinksWithTimeAndWraps)
{
  // speed 0.1 m/s, spacing 0.25 m: phase = (-0.1 t) mod 0.25.
  EXPECT_DOUBLE_EQ(marchingPhase(0.1, 0.0, 0.25), 0.0);
  EXPECT_NEAR(marchingPhase(0.1, 0.5, 0.25), 0.20, 1e-12);   // -0.05 -> 0.20
  EXPECT_NEAR(marchingPhase(0.1, 1.0, 0.25), 0.15, 1e-12);
  EXPECT_NEAR(marchingPhase(0.1, 2.5, 0.25), 0.0, 1e-12);    // -0.25 -> 0
  EXPECT_NEAR(marchingPhase(0.1, -0.5, 0.25), 0.05, 1e-12);  // negative time: +0.05
  EXPECT_NEAR(marchingPhase(0.3, 1700000000.1, 0.25), std::fmod(-0.3 * 1700000000.1, 0.25) + 0.25, 1e-6);
  EXPECT_DOUBLE_EQ(marchingPhase(0.0, 3.0, 0.25), 0.0);
  EXPECT_DOUBLE_EQ(marchingPhase(-1.0, 3.0, 0.25), 0.0);
  EXPECT_DOUBLE_EQ(marchingPhase(kNaN, 3.0, 0.25), 0.0);
  EXPECT_DOUBLE_EQ(marchingPhase(0.1, 3.0, 0.0), 0.0);
}

namespace
{
SpacingParameters exact(double spacing)
{
  SpacingParameters p;
  p.spacing = spacing;  // arrows 0.18 m, circle 0.2 m (r 0.1), gap 0.05
  return p;
}

std::vector<Vec2> straight(double length, double step)
{
  std::vector<Vec2> path;
  for (double x = 0.0; x < length - 1e-9; x += step)
  {
    path.push_back(Vec2{x, 0.0});
  }
  path.push_back(Vec2{length, 0.0});
  return path;
}
}  // namespace

TEST(SpacerPhase, TipsMoveByThePhaseOnAStraightPath)
{
  PathSpacer spacer(exact(0.5));
  const auto path = straight(3.0, 0.3);
  const SpacedPath& a = spacer.space(path, 0.2);
  // Tips at 0.15 + 0.2 + 0.5 k from the end while tip + 0.18 <= 3: k = 0..4 (k = 4: 2.35 + 0.18 = 2.53).
  ASSERT_EQ(a.arrows.size(), 5u);
  for (std::size_t k = 0; k < 5; ++k)
  {
    const double from_end = 0.35 + 0.5 * static_cast<double>(k);
    EXPECT_NEAR(a.tip_from_end[k], from_end, 1e-12);
    EXPECT_NEAR(a.arrows[k].tip.x, 3.0 - from_end, 1e-12);
    EXPECT_NEAR(a.arrows[k].tail.x, 3.0 - from_end - 0.18, 1e-12);
  }
  // Phase 0 is today's static layout; a phase of exactly the spacing wraps to 0; negative wraps up.
  const std::vector<Arrow> still = spacer.space(path, 0.0).arrows;
  const SpacedPath& wrapped = spacer.space(path, 0.5);
  ASSERT_EQ(wrapped.arrows.size(), still.size());
  EXPECT_DOUBLE_EQ(wrapped.arrows[0].tip.x, still[0].tip.x);
  EXPECT_NEAR(spacer.space(path, -0.1).tip_from_end[0], 0.15 + 0.4, 1e-12);
  EXPECT_NEAR(spacer.space(path, kNaN).tip_from_end[0], 0.15, 1e-12);
}

TEST(SpacerPhase, TipsFollowTheArcOnAnL)
{
  PathSpacer spacer(exact(0.5));
  const auto path = lPath();  // 3 m: the last metre goes up x = 2
  const SpacedPath& s = spacer.space(path, 0.1);
  // Tip 0 at 0.25 from the end: (2, 0.75); tip 1 at 0.75: (2, 0.25); tip 2 at 1.25: (1.75, 0).
  ASSERT_GE(s.arrows.size(), 3u);
  EXPECT_NEAR(s.arrows[0].tip.y, 0.75, 1e-12);
  EXPECT_NEAR(s.arrows[1].tip.y, 0.25, 1e-12);
  EXPECT_NEAR(s.arrows[2].tip.x, 1.75, 1e-12);
  EXPECT_NEAR(s.arrows[2].tip.y, 0.0, 1e-12);
}

TEST(SpacerPhase, AReplanOfTheSameRouteChangesNothing)
{
  // The robot advanced 0.8 m along the same route: the replanned path starts later.
  const auto full = straight(4.0, 0.2);
  std::vector<Vec2> trimmed;
  for (const Vec2& p : full)
  {
    if (p.x >= 0.8 - 1e-9)
    {
      trimmed.push_back(p);
    }
  }
  const double t = 12.34;
  const double phase = marchingPhase(0.3, t, 0.5);
  PathSpacer a(exact(0.5)), b(exact(0.5));
  const SpacedPath& before = a.space(full, phase);
  const SpacedPath& after = b.space(trimmed, phase);
  ASSERT_GE(before.arrows.size(), after.arrows.size());
  ASSERT_GT(after.arrows.size(), 3u);
  for (std::size_t k = 0; k < after.arrows.size(); ++k)
  {
    EXPECT_EQ(before.arrows[k].tip.x, after.arrows[k].tip.x) << k;  // bit-identical
    EXPECT_EQ(before.arrows[k].tail.x, after.arrows[k].tail.x) << k;
  }
}

TEST(SpacerPhase, MarchingArrowsNeverJump)
{
  // Each arrow of the frame at t + dt lies within speed * dt of an arrow of the frame at t, except
  // one entering at the start; an arrow of t may vanish only at the destination end.
  const auto path = straight(3.0, 0.1);
  const double speed = 0.4, dt = 1.0 / 60.0, spacing = 0.25;
  PathSpacer spacer(exact(spacing));
  std::vector<double> previous;
  for (int frame = 0; frame < 200; ++frame)
  {
    const double t = frame * dt;
    const SpacedPath& s = spacer.space(path, marchingPhase(speed, t, spacing));
    std::vector<double> now(s.tip_from_end);
    if (!previous.empty())
    {
      int new_ones = 0;
      for (double d : now)
      {
        bool near = false;
        for (double p : previous)
        {
          near = near || (p - d >= -1e-9 && p - d <= speed * dt + 1e-9);  // moved towards the end
        }
        if (!near)
        {
          ++new_ones;
          EXPECT_GT(d + 0.18, 3.0 - spacing) << "a new arrow must enter at the start, frame " << frame;
        }
      }
      EXPECT_LE(new_ones, 1) << "frame " << frame;
      for (double p : previous)
      {
        bool kept = false;
        for (double d : now)
        {
          kept = kept || (p - d >= -1e-9 && p - d <= speed * dt + 1e-9);
        }
        if (!kept)
        {
          EXPECT_LT(p, 0.15 + speed * dt + 1e-9) << "only the arrow at the destination may leave, frame " << frame;
        }
      }
    }
    previous = now;
  }
}

TEST(SpacerPhase, PaperModeReportsTipArcLengths)
{
  SpacingParameters p;
  p.mode = SpacingMode::Paper;
  p.spacing = 0.3;
  PathSpacer spacer(p);
  const auto path = straight(2.0, 0.1);
  const SpacedPath& s = spacer.space(path, 0.17);  // the phase is ignored in Paper mode
  ASSERT_FALSE(s.arrows.empty());
  ASSERT_EQ(s.tip_from_end.size(), s.arrows.size());
  for (std::size_t k = 0; k < s.arrows.size(); ++k)
  {
    EXPECT_NEAR(s.tip_from_end[k], 2.0 - s.arrows[k].tip.x, 1e-9);
  }
}
