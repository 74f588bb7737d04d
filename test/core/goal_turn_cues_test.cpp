// Turn detection, the glyph and cross triangles, and the goal-state cues over time, against
// hand-computed cases.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/goal_cues.h"
#include "rviz_projector/core/path_location.h"
#include "rviz_projector/core/turn_signal.h"

using namespace rviz_projector;

namespace
{
constexpr double kPi = 3.14159265358979323846;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Straight along +x for `before` metres, then turning by `angle` (+: left) and on for 2 m, 1 cm steps.
std::vector<Vec2> bend(double before, double angle)
{
  std::vector<Vec2> path;
  for (int i = 0; i <= static_cast<int>(before * 100); ++i)
  {
    path.push_back(Vec2{0.01 * i, 0.0});
  }
  const Vec2 corner = path.back();
  for (int i = 1; i <= 200; ++i)
  {
    path.push_back(corner + Vec2{std::cos(angle), std::sin(angle)} * (0.01 * i));
  }
  return path;
}

TurnDetection detect(const std::vector<Vec2>& path, double start = 0.0, TurnSignalParameters p = {})
{
  std::vector<double> lengths;
  accumulateArcLengths(path, lengths);
  return detectTurn(path, lengths, start, p);
}

double signedArea(const Vec2& a, const Vec2& b, const Vec2& c)
{
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}
}  // namespace

TEST(TurnSignal, StraightPathHasNoTurn)
{
  const TurnDetection t = detect(bend(3.0, 0.0));
  EXPECT_EQ(t.side, TurnSide::None);
  EXPECT_NEAR(t.heading, 0.0, 1e-12);
}

TEST(TurnSignal, RightAngleOneMetreAheadBySign)
{
  // The 0.2 m chord starts turning 0.2 m before the corner and has turned 45 degrees (the threshold,
  // not yet more) when centred on it, 0.1 m before: more than 45 degrees from 0.9 m ahead on.
  TurnDetection left = detect(bend(1.0, kPi / 2));
  EXPECT_EQ(left.side, TurnSide::Left);
  EXPECT_NEAR(left.ahead, 0.9, 0.05 + 1e-9);
  TurnDetection right = detect(bend(1.0, -kPi / 2));
  EXPECT_EQ(right.side, TurnSide::Right);
  EXPECT_NEAR(right.ahead, 0.9, 0.05 + 1e-9);
}

TEST(TurnSignal, TurnBeyondTheDistanceIsNotSignalled)
{
  EXPECT_EQ(detect(bend(2.0, kPi / 2)).side, TurnSide::None);  // corner 2 m ahead, distance 1.5 m
  TurnSignalParameters far;
  far.distance = 2.5;
  EXPECT_EQ(detect(bend(2.0, kPi / 2), 0.0, far).side, TurnSide::Left);
  // A robot further along: the corner is 0.5 m ahead of it.
  EXPECT_EQ(detect(bend(2.0, kPi / 2), 1.5).side, TurnSide::Left);
}

TEST(TurnSignal, SBendOfTwoThirtyDegreeBendsIsNotATurn)
{
  std::vector<Vec2> path{Vec2{0, 0}};
  const double headings[] = {0.0, kPi / 6, 0.0};  // 0.5 m each: left 30 degrees, then back right
  for (double h : headings)
  {
    for (int i = 0; i < 50; ++i)
    {
      path.push_back(path.back() + Vec2{std::cos(h), std::sin(h)} * 0.01);
    }
  }
  EXPECT_EQ(detect(path).side, TurnSide::None);
}

TEST(TurnSignal, UTurnHasItsSide)
{
  std::vector<Vec2> path;
  for (int i = 0; i <= 50; ++i)
  {
    path.push_back(Vec2{0.01 * i, 0.0});
  }
  for (int i = 1; i <= 60; ++i)  // half circle of radius 0.3 to the right (clockwise)
  {
    const double a = kPi / 2 - kPi * i / 60.0;
    path.push_back(Vec2{0.5 + 0.3 * std::cos(a), -0.3 + 0.3 * std::sin(a)});
  }
  for (int i = 1; i <= 50; ++i)
  {
    path.push_back(Vec2{0.5 - 0.01 * i, -0.6});
  }
  EXPECT_EQ(detect(path).side, TurnSide::Right);
}

TEST(TurnSignal, GridStaircaseDiagonalIsNotATurn)
{
  // A planner's 5 cm grid cells along the diagonal: alternating +x and +y steps.
  std::vector<Vec2> path{Vec2{0, 0}};
  for (int i = 0; i < 60; ++i)
  {
    path.push_back(path.back() + (i % 2 == 0 ? Vec2{0.05, 0.0} : Vec2{0.0, 0.05}));
  }
  EXPECT_EQ(detect(path).side, TurnSide::None);
}

TEST(TurnSignal, BadInputIsNoTurn)
{
  EXPECT_EQ(detect({}).side, TurnSide::None);
  EXPECT_EQ(detect({Vec2{1, 1}}).side, TurnSide::None);
  EXPECT_EQ(detect(bend(1.0, kPi / 2), kNaN).side, TurnSide::None);
  TurnSignalParameters bad;
  bad.step = 0.0;
  EXPECT_EQ(detect(bend(1.0, kPi / 2), 0.0, bad).side, TurnSide::None);
}

TEST(TurnGlyph, OnTheInsideOfTheTurnWithinItsSizeCounterClockwise)
{
  for (TurnSide side : {TurnSide::Left, TurnSide::Right})
  {
    for (double heading : {0.0, 1.0, -2.5})
    {
      std::vector<Vec2> triangles;
      const Vec2 robot{1.0, 2.0};
      appendTurnGlyph(robot, heading, side, 0.8, 0.6, 0.3, triangles);
      ASSERT_FALSE(triangles.empty());
      ASSERT_EQ(triangles.size() % 3, 0u);
      const Vec2 left{-std::sin(heading), std::cos(heading)};
      const Vec2 forward{std::cos(heading), std::sin(heading)};
      const Vec2 centre = robot + forward * 0.8 + left * (side == TurnSide::Left ? 0.6 : -0.6);
      for (std::size_t i = 0; i < triangles.size(); i += 3)
      {
        EXPECT_GT(signedArea(triangles[i], triangles[i + 1], triangles[i + 2]), 0.0);
      }
      for (const Vec2& v : triangles)
      {
        const double sideways = dot(v - robot, left);
        EXPECT_GT(side == TurnSide::Left ? sideways : -sideways, 0.0) << "on the inside of the turn";
        EXPECT_LE(distance(v, centre), 0.3 * std::sqrt(0.5) + 1e-9) << "within half the size's diagonal";
      }
    }
  }
  std::vector<Vec2> none;
  appendTurnGlyph(Vec2{0, 0}, 0.0, TurnSide::None, 0.8, 0.6, 0.3, none);
  appendTurnGlyph(Vec2{0, 0}, kNaN, TurnSide::Left, 0.8, 0.6, 0.3, none);
  appendTurnGlyph(Vec2{0, 0}, 0.0, TurnSide::Left, 0.8, 0.6, -1.0, none);
  EXPECT_TRUE(none.empty());
}

TEST(TurnGlyph, CrossIsSymmetricAroundItsCentre)
{
  std::vector<Vec2> triangles;
  const Vec2 c{3.0, -1.0};
  appendCross(c, 0.2, 0.04, triangles);
  ASSERT_EQ(triangles.size(), 12u);  // two bars, two triangles each
  Vec2 sum;
  for (const Vec2& v : triangles)
  {
    sum = sum + (v - c);
    EXPECT_LE(distance(v, c), std::hypot(0.1, 0.02) + 1e-12);
  }
  EXPECT_NEAR(sum.x, 0.0, 1e-12);
  EXPECT_NEAR(sum.y, 0.0, 1e-12);
  // The bars lie along the diagonals: the farthest corners are near (+-0.0707, +-0.0707) from c.
  bool diagonal = false;
  for (const Vec2& v : triangles)
  {
    diagonal = diagonal || (v.x - c.x > 0.05 && v.y - c.y > 0.05);
  }
  EXPECT_TRUE(diagonal);
}

TEST(GoalCues, BlinkHalves)
{
  EXPECT_TRUE(blinkOn(0.0, 2.0));
  EXPECT_TRUE(blinkOn(0.24, 2.0));
  EXPECT_FALSE(blinkOn(0.25, 2.0));
  EXPECT_FALSE(blinkOn(0.49, 2.0));
  EXPECT_TRUE(blinkOn(0.5, 2.0));
  EXPECT_TRUE(blinkOn(-1.0, 2.0));
  EXPECT_TRUE(blinkOn(kNaN, 2.0));
  EXPECT_TRUE(blinkOn(0.3, 0.0));
}

TEST(GoalCues, SummaryForEachStatusCode)
{
  const GoalPhase expected[] = {GoalPhase::Active, GoalPhase::Active, GoalPhase::Failed, GoalPhase::Succeeded,
                                GoalPhase::Failed, GoalPhase::Failed, GoalPhase::Active, GoalPhase::Active,
                                GoalPhase::Failed, GoalPhase::Failed};
  for (std::uint8_t code = 0; code < 10; ++code)
  {
    const GoalSummary s = summarizeGoals({GoalStatusEntry{"g", 1.0, code}});
    EXPECT_EQ(s.phase, expected[code]) << "status " << int(code);
    EXPECT_EQ(s.id, "g");
  }
  EXPECT_EQ(summarizeGoals({GoalStatusEntry{"g", 1.0, 10}}).phase, GoalPhase::None);
  EXPECT_EQ(summarizeGoals({}).phase, GoalPhase::None);
}

TEST(GoalCues, PreemptedBesideANewActiveGoalIsActiveAndNewestTerminalDecides)
{
  GoalSummary s = summarizeGoals({GoalStatusEntry{"old", 5.0, 2}, GoalStatusEntry{"new", 6.0, 1}});
  EXPECT_EQ(s.phase, GoalPhase::Active);
  EXPECT_EQ(s.id, "new");
  s = summarizeGoals({GoalStatusEntry{"a", 5.0, 4}, GoalStatusEntry{"b", 7.0, 3}, GoalStatusEntry{"c", 6.0, 2}});
  EXPECT_EQ(s.phase, GoalPhase::Succeeded);
  EXPECT_EQ(s.id, "b");
  s = summarizeGoals({GoalStatusEntry{"a", 5.0, 3}, GoalStatusEntry{"b", 5.0, 4}});  // equal stamps: later entry
  EXPECT_EQ(s.id, "b");
}

namespace
{
GoalCueTimeline timeline(bool warning)
{
  GoalCueTimeline t;
  GoalCueParameters p;
  p.warning_enabled = warning;
  p.warning_time = 2.0;
  p.warning_hz = 2.0;
  t.setParameters(p);
  return t;
}
}  // namespace

TEST(GoalCues, WarningBlinksForItsTimeThenSteady)
{
  GoalCueTimeline t = timeline(true);
  t.update(GoalSummary{GoalPhase::Active, "g1"}, 100.0, true);
  const double lit[] = {100.0, 100.1, 100.6, 101.55};
  const double dark[] = {100.3, 100.85, 101.3, 101.99};
  for (double time : lit)
  {
    const GoalCueFrame f = t.frameAt(time);
    EXPECT_TRUE(f.arrows && f.destination && f.warning && f.animating) << time;
  }
  for (double time : dark)
  {
    const GoalCueFrame f = t.frameAt(time);
    EXPECT_TRUE(!f.arrows && !f.destination && f.warning && f.animating) << time;
  }
  for (double time : {102.0, 102.3, 150.0})
  {
    const GoalCueFrame f = t.frameAt(time);
    EXPECT_TRUE(f.arrows && f.destination && !f.warning && !f.animating) << time;
  }
  // The same goal again (status messages repeat): no second warning; the robot moving changes nothing.
  t.update(GoalSummary{GoalPhase::Active, "g1"}, 103.0, false);
  EXPECT_TRUE(t.frameAt(103.3).arrows);
}

TEST(GoalCues, AGoalIssuedLongerThanTheWarningTimeAgoGetsNoWarning)
{
  // rviz started (or the State topic set) while the robot already pursues a goal issued at t = 50:
  // at t = 100 it is not new to anyone around, even if the robot happens to stand still.
  GoalCueTimeline t = timeline(true);
  t.update(GoalSummary{GoalPhase::Active, "g1", 50.0}, 100.0, true);
  EXPECT_FALSE(t.frameAt(100.3).warning);
  EXPECT_TRUE(t.frameAt(100.3).arrows) << "steady, not blinking";
  // Issued 1.5 s ago (< 2 s warning time): warned, from now for the full warning time.
  GoalCueTimeline u = timeline(true);
  u.update(GoalSummary{GoalPhase::Active, "g2", 98.5}, 100.0, true);
  EXPECT_TRUE(u.frameAt(100.3).warning);
  EXPECT_FALSE(u.frameAt(100.3).arrows) << "dark half of the first period";
  // A goal stamped in the future (another clock) or 0 (unknown): judged new.
  GoalCueTimeline v = timeline(true);
  v.update(GoalSummary{GoalPhase::Active, "g3", 0.0}, 100.0, true);
  EXPECT_TRUE(v.frameAt(100.3).warning);
}

TEST(GoalCues, AStartedWarningRunsItsFullTimeWhenTheRobotStartsMoving)
{
  GoalCueTimeline t = timeline(true);
  t.update(GoalSummary{GoalPhase::Active, "g1"}, 100.0, true);
  t.update(GoalSummary{GoalPhase::Active, "g1"}, 100.5, false);  // the robot moves 0.5 s in
  EXPECT_FALSE(t.frameAt(100.85).arrows) << "still blinking (dark half)";
  EXPECT_TRUE(t.frameAt(100.85).warning);
  EXPECT_TRUE(t.frameAt(101.6).arrows);
  EXPECT_TRUE(t.frameAt(101.6).warning);
}

TEST(GoalCues, NoWarningWhenMovingOrDisabledAndANewGoalWarnsAgain)
{
  GoalCueTimeline t = timeline(true);
  t.update(GoalSummary{GoalPhase::Active, "g1"}, 10.0, false);  // moving at activation
  EXPECT_TRUE(t.frameAt(10.3).arrows);
  EXPECT_FALSE(t.frameAt(10.3).animating);
  t.update(GoalSummary{GoalPhase::Active, "g2"}, 20.0, true);  // a new goal while standing
  EXPECT_FALSE(t.frameAt(20.3).arrows);
  GoalCueTimeline off = timeline(false);
  off.update(GoalSummary{GoalPhase::Active, "g1"}, 10.0, true);
  EXPECT_TRUE(off.frameAt(10.3).arrows);
}

TEST(GoalCues, SuccessFlashesThenClearsAndFailureCrossesSteadily)
{
  GoalCueTimeline t = timeline(false);
  t.update(GoalSummary{GoalPhase::Active, "g"}, 1.0, false);
  t.update(GoalSummary{GoalPhase::Succeeded, "g"}, 5.0, true);
  GoalCueFrame f = t.frameAt(5.2);
  EXPECT_FALSE(f.arrows);
  EXPECT_TRUE(f.destination);
  EXPECT_EQ(f.colour, GoalCueFrame::Colour::Succeeded);
  EXPECT_TRUE(f.animating);
  t.update(GoalSummary{GoalPhase::Succeeded, "g"}, 5.4, true);  // repeated status: the flash keeps its start
  f = t.frameAt(5.6);
  EXPECT_FALSE(f.arrows || f.destination || f.animating);
  t.update(GoalSummary{GoalPhase::Failed, "h"}, 7.0, true);
  for (double time : {7.0, 9.0, 100.0})
  {
    f = t.frameAt(time);
    EXPECT_TRUE(!f.arrows && f.destination && f.cross && !f.animating) << time;
    EXPECT_EQ(f.colour, GoalCueFrame::Colour::Failed);
  }
  t.update(GoalSummary{GoalPhase::None, ""}, 8.0, true);
  f = t.frameAt(8.0);
  EXPECT_TRUE(f.arrows && f.destination && !f.cross);
}

TEST(GoalCues, TimeBackwardsRestartsAndNaNIsIgnored)
{
  GoalCueTimeline t = timeline(true);
  t.update(GoalSummary{GoalPhase::Active, "g"}, 50.0, true);
  EXPECT_TRUE(t.frameAt(40.0).warning);  // before the start: as if it started now (lit)
  EXPECT_TRUE(t.frameAt(40.0).arrows);
  t.update(GoalSummary{GoalPhase::Active, "g"}, 10.0, true);  // bag loop
  EXPECT_FALSE(t.frameAt(10.3).arrows);                       // warning restarted at 10
  t.update(GoalSummary{GoalPhase::Failed, "x"}, kNaN, true);
  EXPECT_EQ(t.phase(), GoalPhase::Active);
}

TEST(Stillness, StillMovingUnknownStaleOutOfOrder)
{
  StillnessDetector d(0.5, 0.02, 1.0);
  EXPECT_TRUE(d.still(0.0));  // unknown
  for (int i = 0; i <= 10; ++i)
  {
    d.add(Vec2{0.001 * (i % 2), 0.0}, 0.1 * i);  // 1 mm jitter
  }
  EXPECT_TRUE(d.still(1.0));
  for (int i = 11; i <= 20; ++i)
  {
    d.add(Vec2{0.01 * (i - 10), 0.0}, 0.1 * i);  // 1 cm per 0.1 s
  }
  EXPECT_FALSE(d.still(2.0));
  EXPECT_TRUE(d.still(3.5));  // newest sample 1.5 s old: unknown -> still
  d.add(Vec2{5.0, 5.0}, 0.5);  // time went backwards: history cleared
  EXPECT_TRUE(d.still(0.5));
  d.add(Vec2{kNaN, 0.0}, 0.6);
  EXPECT_TRUE(d.still(0.6));
}
