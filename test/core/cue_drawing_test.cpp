// CueDrawing: what ProjectedPath draws once its cues apply, against hand-computed arrow places,
// horizon opacities and goal frames (a straight path; Exact spacing).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/cue_drawing.h"
#include "rviz_projector/core/path_spacer.h"

using namespace rviz_projector;

namespace
{
/// (0, 0) -> (5, 0) every 0.5 m.
std::vector<Vec2> straightPath()
{
  std::vector<Vec2> path;
  for (int i = 0; i <= 10; ++i)
  {
    path.push_back(Vec2{0.5 * i, 0.0});
  }
  return path;
}

SpacingParameters parameters()
{
  SpacingParameters p;
  p.spacing = 0.5;  // arrows 0.18 m long (0.1 shaft + 0.08 head), circle 0.2 m, gap 0.05 m
  return p;
}

/// The x of arrow `index`'s tip in the drawing: its head triangle's apex is vertex 7 of 9 (the
/// tip), read from the triangles; found as the vertex with the largest x of that arrow.
double tipX(const CueDrawing& d, std::size_t index)
{
  double x = -1e9;
  for (std::size_t v = 0; v < ArrowOutline::kVerticesPerArrow; ++v)
  {
    x = std::max(x, d.arrows()[index * ArrowOutline::kVerticesPerArrow + v].x);
  }
  return x;
}
}  // namespace

TEST(CueDrawing, NoCueDrawsEveryArrowOpaqueAndTheCircle)
{
  PathSpacer spacer(parameters());
  const auto path = straightPath();
  CueDrawing d;
  d.build(path, spacer.space(path), parameters(), PathCueSettings(), PathCueInput());
  // Tips at 0.15 + 0.5 k from the end while the tail (tip + 0.18) stays on the 5 m path: k = 0..9.
  EXPECT_EQ(d.arrowsDrawn(), 10u);
  ASSERT_EQ(d.arrowAlpha().size(), 90u);
  for (float a : d.arrowAlpha())
  {
    EXPECT_EQ(a, 1.0f);
  }
  EXPECT_FALSE(d.destination().empty());
  EXPECT_FALSE(d.cross());
  EXPECT_TRUE(d.glyph().empty());
  EXPECT_FALSE(d.animating());
}

TEST(CueDrawing, HorizonKeepsArrowsAheadOfTheRobotAndFadesByTipArcLength)
{
  PathSpacer spacer(parameters());
  const auto path = straightPath();
  PathCueSettings settings;
  settings.horizon = true;
  settings.horizon_length = 2.0;
  settings.fade_length = 1.0;
  PathCueInput input;
  input.robot_known = true;
  input.robot = Vec2{1.0, 0.3};  // nearest path point (1, 0): arc length 1.0 -> window [1, 3], fade from 2
  CueDrawing d;
  d.build(path, spacer.space(path), parameters(), settings, input);
  // Tips at x = 5 - 0.15 - 0.5 k = 4.85, 4.35, 3.85, 3.35 (beyond 3: hidden), 2.85 (alpha 0.15),
  // 2.35 (0.65), 1.85, 1.35 (1), 0.85, 0.35 (behind the robot: hidden). Destination at 5: hidden.
  ASSERT_EQ(d.arrowsDrawn(), 4u);
  const double tips[] = {2.85, 2.35, 1.85, 1.35};
  const float alphas[] = {0.15f, 0.65f, 1.0f, 1.0f};
  for (std::size_t i = 0; i < 4; ++i)
  {
    EXPECT_NEAR(tipX(d, i), tips[i], 1e-9) << "arrow " << i;
    for (std::size_t v = 0; v < ArrowOutline::kVerticesPerArrow; ++v)
    {
      EXPECT_NEAR(d.arrowAlpha()[i * ArrowOutline::kVerticesPerArrow + v], alphas[i], 1e-6) << "arrow " << i;
    }
  }
  EXPECT_TRUE(d.destination().empty());
}

TEST(CueDrawing, HorizonWithoutARobotStartsAtThePathStart)
{
  PathSpacer spacer(parameters());
  const auto path = straightPath();
  PathCueSettings settings;
  settings.horizon = true;
  settings.horizon_length = 1.0;
  settings.fade_length = 0.0;
  CueDrawing d;
  d.build(path, spacer.space(path), parameters(), settings, PathCueInput());  // robot unknown
  // Window [0, 1]: tips at 0.85 and 0.35.
  ASSERT_EQ(d.arrowsDrawn(), 2u);
  EXPECT_NEAR(tipX(d, 0), 0.85, 1e-9);
  EXPECT_NEAR(tipX(d, 1), 0.35, 1e-9);
}

TEST(CueDrawing, FailedGoalHidesArrowsAndCrossesTheDestination)
{
  PathSpacer spacer(parameters());
  const auto path = straightPath();
  PathCueInput input;
  input.goal.arrows = false;
  input.goal.cross = true;
  input.goal.colour = GoalCueFrame::Colour::Failed;
  CueDrawing d;
  d.build(path, spacer.space(path), parameters(), PathCueSettings(), input);
  EXPECT_EQ(d.arrowsDrawn(), 0u);
  EXPECT_TRUE(d.cross());
  ASSERT_FALSE(d.destination().empty());
  // The cross lies around the destination (5, 0), within its 0.2 m size (plus the bars' half width).
  for (const Vec2& v : d.destination())
  {
    EXPECT_LE(std::hypot(v.x - 5.0, v.y), 0.1 * std::sqrt(2.0) + 0.03);
  }
}

TEST(CueDrawing, HiddenDestinationAndArrowsDrawNothing)
{
  PathSpacer spacer(parameters());
  const auto path = straightPath();
  PathCueInput input;
  input.goal.arrows = false;
  input.goal.destination = false;
  input.goal.animating = true;
  CueDrawing d;
  d.build(path, spacer.space(path), parameters(), PathCueSettings(), input);
  EXPECT_EQ(d.arrowsDrawn(), 0u);
  EXPECT_TRUE(d.destination().empty());
  EXPECT_TRUE(d.animating());  // the goal frame blinks: frames keep coming
}

TEST(CueDrawing, TurnGlyphBlinksFromTimeZero)
{
  // Straight 1 m along +x, then 2 m along +y: a left turn 1 m ahead of a robot at the start.
  std::vector<Vec2> path;
  for (int i = 0; i <= 10; ++i)
  {
    path.push_back(Vec2{0.1 * i, 0.0});
  }
  for (int i = 1; i <= 20; ++i)
  {
    path.push_back(Vec2{1.0, 0.1 * i});
  }
  PathSpacer spacer(parameters());
  PathCueSettings settings;
  settings.turn_signal = true;
  PathCueInput input;
  input.robot_known = true;
  input.robot = Vec2{0.0, 0.0};
  input.time = 0.1;  // 1.5 Hz: lit while frac(1.5 t) < 0.5, i.e. t in [0, 1/3)
  CueDrawing d;
  d.build(path, spacer.space(path), parameters(), settings, input);
  EXPECT_EQ(d.turn().side, TurnSide::Left);
  EXPECT_FALSE(d.glyph().empty());
  EXPECT_TRUE(d.animating());
  for (const Vec2& v : d.glyph())
  {
    EXPECT_GT(v.y, 0.0) << "the glyph lies on the left of a robot heading +x";
  }
  input.time = 0.5;  // frac(0.75): dark half
  d.build(path, spacer.space(path), parameters(), settings, input);
  EXPECT_TRUE(d.glyph().empty());
  EXPECT_TRUE(d.animating());
}

TEST(CueDrawing, MarchingAnimatesInExactModeOnly)
{
  PathSpacer spacer(parameters());
  const auto path = straightPath();
  PathCueSettings settings;
  settings.marching = true;
  CueDrawing d;
  d.build(path, spacer.space(path), parameters(), settings, PathCueInput());
  EXPECT_TRUE(d.animating());
  SpacingParameters paper = parameters();
  paper.mode = SpacingMode::Paper;
  spacer.setParameters(paper);
  d.build(path, spacer.space(path), paper, settings, PathCueInput());
  EXPECT_FALSE(d.animating());
}
