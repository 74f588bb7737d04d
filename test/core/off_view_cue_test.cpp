// The off-view cue (issue 25, part 3) on cases worked out by hand. The robot stands at the origin
// facing +x; the projector lights the rectangle x in [0.3, 1.3], y in [-0.4, 0.4] in front of it
// (1 m x 0.8 m, given clockwise as FloorFootprint's outline is). Default parameters: look-ahead
// 1.5 m, margin 0.15 m (so arrow tips stay in x in [0.45, 1.15], y in [-0.25, 0.25]), arrows 0.3 m
// long, heads 0.12 m wide, hysteresis 0.25 / 0.4, turn in place beyond 60 degrees, final approach
// 1 m, path clearance 0.1 m. The overlap check samples the path every 5 mm and measures the distance
// to every cue triangle itself (not the code's segment tests).
#include "rviz_projector/core/off_view_cue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/path_location.h"

namespace rviz_projector
{
namespace
{
const std::vector<Vec2> kLit{{0.3, 0.4}, {1.3, 0.4}, {1.3, -0.4}, {0.3, -0.4}};

struct Case
{
  std::vector<Vec2> points;
  std::vector<double> lengths;
  OffViewInput input;
};

Case makeCase(std::vector<Vec2> points, std::vector<Vec2> lit = kLit)
{
  Case c;
  c.points = std::move(points);
  accumulateArcLengths(c.points, c.lengths);
  c.input.lit = std::move(lit);
  c.input.robot = {0, 0};
  c.input.heading = 0.0;
  c.input.start = 0.0;
  return c;
}

double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b)
{
  const Vec2 ab = b - a;
  const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
  return distance(p, a + ab * t);
}

double distanceToTriangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c)
{
  const auto side = [](const Vec2& o, const Vec2& u, const Vec2& v) {
    return (u.x - o.x) * (v.y - o.y) - (u.y - o.y) * (v.x - o.x);
  };
  const double d1 = side(a, b, p), d2 = side(b, c, p), d3 = side(c, a, p);
  if ((d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0))
  {
    return 0.0;
  }
  return std::min({distanceToSegment(p, a, b), distanceToSegment(p, b, c), distanceToSegment(p, c, a)});
}

/// Smallest distance from the path ahead of `start` (sampled every 5 mm) to any triangle.
double clearanceToPath(const Case& c, const std::vector<Vec2>& triangles)
{
  double best = std::numeric_limits<double>::infinity();
  for (double s = c.input.start; s <= c.lengths.back(); s += 0.005)
  {
    const Vec2 p = pointAtArcLength(c.points, c.lengths, s);
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
    {
      best = std::min(best, distanceToTriangle(p, triangles[t], triangles[t + 1], triangles[t + 2]));
    }
  }
  return best;
}

bool insideLit(const Vec2& p)
{
  return p.x >= 0.3 - 1e-9 && p.x <= 1.3 + 1e-9 && p.y >= -0.4 - 1e-9 && p.y <= 0.4 + 1e-9;
}

bool hasVertexNear(const std::vector<Vec2>& triangles, const Vec2& q, double tolerance)
{
  return std::any_of(triangles.begin(), triangles.end(), [&](const Vec2& p) { return distance(p, q) < tolerance; });
}

TEST(OffViewCue, PathStraightAheadIsVisible)
{
  // Window [0, 1.5] along y = 0; inside x in [0.3, 1.3]: 1.0 m of 1.5 -> 2/3.
  Case c = makeCase({{0, 0}, {3, 0}});
  OffViewCue cue;
  const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(r.kind, OffViewKind::None);
  EXPECT_NEAR(r.visible_fraction, 2.0 / 3.0, 1e-9);
  EXPECT_TRUE(r.triangles.empty());
  EXPECT_EQ(r.reason, "path visible");
  EXPECT_TRUE(r.by_design);  // a status of Ok, not a warning
  // The window starts at the robot's place on the path: path from (-1, 0), robot 1 m along it at the
  // origin: the same 2/3. Judged from the path's first point instead, [-1, 0.5] would hold 0.2 m
  // lit (0.133: a cue).
  Case behind = makeCase({{-1, 0}, {3, 0}});
  behind.input.start = 1.0;
  EXPECT_EQ(cue.build(behind.points, behind.lengths, behind.input, OffViewParameters()).kind, OffViewKind::None);
  EXPECT_NEAR(cue.result().visible_fraction, 2.0 / 3.0, 1e-9);
}

TEST(OffViewCue, PathTurningLeftBeforeTheLitAreaGetsAnArrowOnTheLeftEdge)
{
  // (0,0) -> (0.2,0) -> (0.2,2): direction at the robot +x (no turn in place), 2.2 m left (no final
  // approach), nothing inside the lit area (x = 0.2 < 0.3). Target: the window's end, arc 1.5 ->
  // (0.2, 1.3); the shrunk area's nearest point: (0.45, 0.25); the path's direction there +y. The
  // arrow (x in [0.39, 0.51]) is 0.19 m from the path at x = 0.2: no shift.
  Case c = makeCase({{0, 0}, {0.2, 0}, {0.2, 2}});
  OffViewCue cue;
  const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(r.kind, OffViewKind::EdgeArrow);
  EXPECT_EQ(r.visible_fraction, 0.0);
  EXPECT_NEAR(r.anchor.x, 0.45, 1e-4);
  EXPECT_NEAR(r.anchor.y, 0.25, 1e-4);
  EXPECT_NEAR(r.direction.x, 0.0, 1e-9);
  EXPECT_NEAR(r.direction.y, 1.0, 1e-9);
  EXPECT_EQ(r.scale, 1.0);
  ASSERT_EQ(r.triangles.size(), 9u);
  // Tip (0.45, 0.25), tail 0.3 m back at (0.45, -0.05).
  EXPECT_TRUE(hasVertexNear(r.triangles, {0.45, 0.25}, 1e-4));
  EXPECT_TRUE(hasVertexNear(r.triangles, {0.45 - 0.03, -0.05}, 1e-4));
  EXPECT_TRUE(hasVertexNear(r.triangles, {0.45 + 0.03, -0.05}, 1e-4));
  for (const Vec2& p : r.triangles)
  {
    EXPECT_TRUE(insideLit(p)) << p.x << ", " << p.y;
  }
  EXPECT_GE(clearanceToPath(c, r.triangles), 0.1 - 1e-3);
}

TEST(OffViewCue, ArrowWhereThePathLeavesShiftsAwayFromTheVisiblePath)
{
  // Look-ahead 3 m. (0,0) -> (0.4,0) -> (0.4,-1) -> (2.4,-1): inside 0.1 m (x 0.3..0.4) + 0.4 m
  // (y 0..-0.4) = 0.5 of 3 -> 1/6. It last leaves at (0.4, -0.4) (arc 0.8), heading -y (the
  // window's end, (2.0, -1) heading +x, is not where it leaves). The shrunk area's nearest
  // point is (0.45, -0.25); there the head's inner corner (x 0.39) lies on the path at x = 0.4. The
  // sideways steps (5 cm, +x first since the left of -y is +x): the inner corner tip.x - 0.06 must be
  // >= 0.4 + 0.1 -> tip.x >= 0.56 -> the third step, 0.45 + 0.15 = 0.6.
  Case c = makeCase({{0, 0}, {0.4, 0}, {0.4, -1}, {2.4, -1}});
  OffViewParameters parameters;
  parameters.look_ahead = 3.0;
  OffViewCue cue;
  const OffViewResult& r = cue.build(c.points, c.lengths, c.input, parameters);
  EXPECT_EQ(r.kind, OffViewKind::EdgeArrow);
  EXPECT_NEAR(r.visible_fraction, 1.0 / 6.0, 1e-9);
  EXPECT_NEAR(r.direction.x, 0.0, 1e-9);
  EXPECT_NEAR(r.direction.y, -1.0, 1e-9);
  EXPECT_NEAR(r.anchor.x, 0.6, 1e-4);
  EXPECT_NEAR(r.anchor.y, -0.25, 1e-4);
  ASSERT_EQ(r.triangles.size(), 9u);
  for (const Vec2& p : r.triangles)
  {
    EXPECT_TRUE(insideLit(p)) << p.x << ", " << p.y;
  }
  EXPECT_GE(clearanceToPath(c, r.triangles), 0.1 - 1e-3);
}

TEST(OffViewCue, GoalBehindTurnsInPlaceToTheSideOfTheDifference)
{
  // Path towards (-2, -0.2): heading atan2(-0.2, -2) = -174.3 deg, 174.3 deg right of the robot's
  // heading -> Right. Glyph centred on the lit area's centroid (0.8, 0). Glyph box (turn_signal.h,
  // size 0.3): u in [0, 0.15 + 0.066], v in [-0.03, 0.15 + 0.135]; centre (0.108, 0.1275); the
  // head's tip at (u, v) = (0.15, 0.285) -> 0.042 forwards, 0.1575 towards the turn: (0.842, -0.1575)
  // for Right, (0.842, +0.1575) for Left.
  OffViewCue cue;
  {
    Case c = makeCase({{0, 0}, {-2, -0.2}});
    const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
    EXPECT_EQ(r.kind, OffViewKind::TurnInPlace);
    EXPECT_EQ(r.turn, TurnSide::Right);
    EXPECT_NEAR(r.anchor.x, 0.8, 1e-9);
    EXPECT_NEAR(r.anchor.y, 0.0, 1e-9);
    EXPECT_TRUE(hasVertexNear(r.triangles, {0.842, -0.1575}, 1e-6));
    EXPECT_FALSE(hasVertexNear(r.triangles, {0.842, 0.1575}, 1e-3));
    EXPECT_EQ(r.reason, "turn in place, right");
  }
  {
    Case c = makeCase({{0, 0}, {-2, 0.2}});
    const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
    EXPECT_EQ(r.kind, OffViewKind::TurnInPlace);
    EXPECT_EQ(r.turn, TurnSide::Left);
    EXPECT_TRUE(hasVertexNear(r.triangles, {0.842, 0.1575}, 1e-6));
    for (const Vec2& p : r.triangles)
    {
      EXPECT_TRUE(insideLit(p)) << p.x << ", " << p.y;
    }
  }
  {
    // Exactly behind: +180 degrees -> Left (documented).
    Case c = makeCase({{0, 0}, {-2, 0}});
    EXPECT_EQ(cue.build(c.points, c.lengths, c.input, OffViewParameters()).turn, TurnSide::Left);
  }
  {
    // A goal beside the robot: path along +y, 90 > 60 degrees -> turn in place, Left.
    Case c = makeCase({{0, 0}, {0, 2}});
    const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
    EXPECT_EQ(r.kind, OffViewKind::TurnInPlace);
    EXPECT_EQ(r.turn, TurnSide::Left);
  }
  {
    // 50 degrees (under 60) is no turn in place: the path to (cos 50, sin 50) * 2 never enters the
    // lit area far enough -> an edge arrow.
    const double a = 50.0 * M_PI / 180.0;
    Case c = makeCase({{0, 0}, {2 * std::cos(a), 2 * std::sin(a)}});
    EXPECT_EQ(cue.build(c.points, c.lengths, c.input, OffViewParameters()).kind, OffViewKind::EdgeArrow);
  }
}

TEST(OffViewCue, KeepsClearOfThePathThatIsDrawnBehindTheRobot)
{
  // The path comes from (0.8, 0), through the lit area, to the robot at the origin (arc 0.8) and on
  // towards (-2, -0.2): turn in place (right), glyph at the centroid (0.8, 0). When the whole path
  // is drawn (drawn_from 0), its part behind the robot runs through the glyph's place: the glyph
  // moves to keep 0.1 m from it. When only the path ahead is drawn (drawn_from = start), the glyph
  // stays at (0.8, 0).
  Case c = makeCase({{0.8, 0}, {0, 0}, {-2, -0.2}});
  c.input.start = 0.8;
  OffViewCue cue;
  c.input.drawn_from = 0.0;
  const OffViewResult whole = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(whole.kind, OffViewKind::TurnInPlace);
  EXPECT_EQ(whole.turn, TurnSide::Right);
  ASSERT_FALSE(whole.triangles.empty());
  Case from_start = c;
  from_start.input.start = 0.0;  // clearanceToPath samples from input.start: the whole path
  EXPECT_GE(clearanceToPath(from_start, whole.triangles), 0.1 - 1e-3);
  c.input.drawn_from = 0.8;
  const OffViewResult ahead = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_NEAR(ahead.anchor.x, 0.8, 1e-9);
  EXPECT_NEAR(ahead.anchor.y, 0.0, 1e-9);
  EXPECT_LT(clearanceToPath(from_start, ahead.triangles), 0.1);  // it covers the part not drawn
}

TEST(OffViewCue, FinalApproachPointsAtTheDestinationWithItsDistance)
{
  // Destination (0.4, 0.45), 0.602 m straight from the robot at 48.4 deg (< 60: no turn in place),
  // outside the lit area (y > 0.4). Inside part: from x = 0.3 (t = 0.75) to y = 0.4 (t = 0.8889):
  // 0.1389 of the path -> fraction 0.139. Tip: the shrunk area's point nearest the destination,
  // (0.45, 0.25); direction (0.4 - 0.45, 0.45 - 0.25) / 0.2062 = (-0.2425, 0.9701). The tip is 0.170
  // from the path's line, the head's corners farther: no shift. Label "0.6 m".
  Case c = makeCase({{0, 0}, {0.4, 0.45}});
  OffViewCue cue;
  const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(r.kind, OffViewKind::Destination);
  EXPECT_NEAR(r.visible_fraction, 0.8889 - 0.75, 1e-3);
  EXPECT_NEAR(r.anchor.x, 0.45, 1e-4);
  EXPECT_NEAR(r.anchor.y, 0.25, 1e-4);
  EXPECT_NEAR(r.direction.x, -0.2425, 1e-3);
  EXPECT_NEAR(r.direction.y, 0.9701, 1e-3);
  EXPECT_EQ(r.label, "0.6 m");
  EXPECT_EQ(r.reason, "destination 0.6 m away");
  // Arrow (9 vertices) then the label: '0' 6 boxes, '.' 1, '6' 6, 'm' 4 -> 17 x 6 vertices.
  ASSERT_EQ(r.triangles.size(), 9u + 17u * 6u);
  const std::vector<Vec2> arrow(r.triangles.begin(), r.triangles.begin() + 9);
  const std::vector<Vec2> label(r.triangles.begin() + 9, r.triangles.end());
  for (const Vec2& p : r.triangles)
  {
    EXPECT_TRUE(insideLit(p)) << p.x << ", " << p.y;
  }
  EXPECT_GE(clearanceToPath(c, r.triangles), 0.1 - 1e-3);
  // The label keeps off the arrow: no label vertex within an arrow triangle, none within 2 cm.
  for (const Vec2& p : label)
  {
    for (std::size_t t = 0; t < 9; t += 3)
    {
      EXPECT_GE(distanceToTriangle(p, arrow[t], arrow[t + 1], arrow[t + 2]), 0.02 - 1e-6);
    }
  }
  // Not final approach when the path left (0.602 m) exceeds it: an edge arrow instead.
  OffViewParameters shorter;
  shorter.final_approach = 0.5;
  OffViewCue other;
  EXPECT_EQ(other.build(c.points, c.lengths, c.input, shorter).kind, OffViewKind::EdgeArrow);
}

TEST(OffViewCue, DestinationInsideTheLitAreaNeedsNoDestinationCue)
{
  // Destination (0.7, 0.3) is lit: it is the path that is judged. Path (0,0) -> (0.7,0.3), 0.762 m,
  // 23 deg; inside from x = 0.3 (t = 0.4286) to the end: 0.5714 of it -> None.
  Case c = makeCase({{0, 0}, {0.7, 0.3}});
  OffViewCue cue;
  const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(r.kind, OffViewKind::None);
  EXPECT_NEAR(r.visible_fraction, 1.0 - 0.3 / 0.7, 1e-9);
}

TEST(OffViewCue, ALitDestinationIsEnoughEvenWhenLittleOfThePathIs)
{
  // Path (0,0) -> (0.35,0): only its last 5 cm are lit (0.05 / 0.35 = 14 % < 25 %), but the
  // destination (0.35, 0) is inside the lit area: its circle shows where the robot goes -> None.
  Case c = makeCase({{0, 0}, {0.35, 0}});
  OffViewCue cue;
  const OffViewResult& r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(r.kind, OffViewKind::None);
  EXPECT_EQ(r.reason, "destination visible");
  EXPECT_TRUE(r.by_design);
  EXPECT_TRUE(r.triangles.empty());
  EXPECT_NEAR(r.visible_fraction, 0.05 / 0.35, 1e-9);
  // The same destination 1 cm before the lit area: a cue.
  Case out = makeCase({{0, 0}, {0.29, 0}});
  EXPECT_NE(cue.build(out.points, out.lengths, out.input, OffViewParameters()).kind, OffViewKind::None);
}

TEST(OffViewCue, HysteresisKeepsTheCueBetweenTheThresholds)
{
  // Straight path along y = 0; lit x in [a, a + 1], y in [-0.4, 0.4]: inside the window [0, 1.5] is
  // 1.5 - a. a = 1.2 -> 0.2 (< 0.25: shown), a = 1.0 -> 1/3 (between: kept as it was), a = 0.8 ->
  // 0.467 (>= 0.4: hidden).
  const auto lit = [](double a) { return std::vector<Vec2>{{a, 0.4}, {a + 1, 0.4}, {a + 1, -0.4}, {a, -0.4}}; };
  const std::vector<Vec2> path{{0, 0}, {3, 0}};
  OffViewCue cue;
  Case c = makeCase(path, lit(1.0));
  EXPECT_EQ(cue.build(c.points, c.lengths, c.input, OffViewParameters()).kind, OffViewKind::None);  // fresh: hidden
  c.input.lit = lit(1.2);
  const OffViewResult& shown = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_NEAR(shown.visible_fraction, 0.2, 1e-9);
  EXPECT_EQ(shown.kind, OffViewKind::EdgeArrow);
  EXPECT_FALSE(shown.triangles.empty());
  EXPECT_GE(clearanceToPath(c, shown.triangles), 0.1 - 1e-3);  // the path runs through the lit area
  c.input.lit = lit(1.0);
  EXPECT_NEAR(cue.build(c.points, c.lengths, c.input, OffViewParameters()).visible_fraction, 1.0 / 3.0, 1e-9);
  EXPECT_EQ(cue.result().kind, OffViewKind::EdgeArrow);  // kept
  EXPECT_TRUE(cue.shown());
  c.input.lit = lit(0.8);
  EXPECT_EQ(cue.build(c.points, c.lengths, c.input, OffViewParameters()).kind, OffViewKind::None);  // gone
  c.input.lit = lit(1.0);
  EXPECT_EQ(cue.build(c.points, c.lengths, c.input, OffViewParameters()).kind, OffViewKind::None);  // stays gone
  EXPECT_FALSE(cue.shown());
}

TEST(OffViewCue, NoRoomBesideTheVisiblePathDrawsNothingAndSaysSo)
{
  // A lit strip y in [-0.15, 0.15] over a straight path (margin 0.05 m, the cue forced by a high
  // threshold): even at half size (head half width 0.03) an arrow clear of the path by 0.1 m has
  // its centre line at >= 0.13 and its head reaching 0.16 > 0.15: no placement.
  Case c = makeCase({{0, 0}, {3, 0}}, {{0.3, 0.15}, {1.3, 0.15}, {1.3, -0.15}, {0.3, -0.15}});
  OffViewParameters parameters;
  parameters.show_below = 0.9;
  parameters.hide_above = 0.9;
  parameters.margin = 0.05;
  OffViewCue cue;
  const OffViewResult& r = cue.build(c.points, c.lengths, c.input, parameters);
  EXPECT_EQ(r.kind, OffViewKind::EdgeArrow);
  EXPECT_TRUE(r.triangles.empty());
  EXPECT_EQ(r.reason, "path leaves the lit area (no room clear of the visible path)");
}

TEST(OffViewCue, ShiftsOrShrinksToFitBesideThePath)
{
  // Strip y in [-0.3, 0.3]: full size needs the centre line >= 0.06 + 0.1 = 0.16 from the path: the
  // 5 cm steps give 0.2, the head reaching 0.26 <= 0.3: it fits, at y = +0.2 (left first).
  // Strip y in [-0.25, 0.25]: full size at 0.15 is too near (0.09), at 0.2 sticks out (0.26); at 3/4
  // (head half width 0.045) 0.15 keeps 0.105 and reaches 0.195: scale 0.75 at y = +0.15.
  OffViewParameters parameters;
  parameters.show_below = 0.9;
  parameters.hide_above = 0.9;
  for (const double half : {0.3, 0.25})
  {
    Case c = makeCase({{0, 0}, {3, 0}}, {{0.3, half}, {1.3, half}, {1.3, -half}, {0.3, -half}});
    OffViewCue cue;
    const OffViewResult& r = cue.build(c.points, c.lengths, c.input, parameters);
    EXPECT_EQ(r.kind, OffViewKind::EdgeArrow);
    ASSERT_EQ(r.triangles.size(), 9u);
    EXPECT_NEAR(r.anchor.y, half == 0.3 ? 0.2 : 0.15, 1e-4);
    EXPECT_EQ(r.scale, half == 0.3 ? 1.0 : 0.75);
    EXPECT_GE(clearanceToPath(c, r.triangles), 0.1 - 1e-3);
    for (const Vec2& p : r.triangles)
    {
      EXPECT_LE(std::abs(p.y), half + 1e-9);
    }
  }
}

TEST(OffViewCue, BadInputGivesNoneWithAReason)
{
  const OffViewParameters parameters;
  OffViewCue cue;
  bool by_design = false;
  const auto reasonFor = [&](Case c) {
    const OffViewResult& r = cue.build(c.points, c.lengths, c.input, parameters);
    EXPECT_EQ(r.kind, OffViewKind::None);
    EXPECT_TRUE(r.triangles.empty());
    EXPECT_FALSE(cue.shown());
    by_design = r.by_design;
    // Every refusal of unusable input is a warning; only "arrived" is the design working.
    EXPECT_EQ(r.by_design, r.reason == "arrived (no path ahead)") << r.reason;
    return r.reason;
  };
  const std::vector<Vec2> path{{0, 0}, {0.2, 0}, {0.2, 2}};  // would give an edge arrow
  EXPECT_EQ(reasonFor(makeCase({})), "no path");
  EXPECT_EQ(reasonFor(makeCase({{0, 0}})), "no path");
  {
    Case c = makeCase(path);
    c.lengths.pop_back();
    EXPECT_EQ(reasonFor(c), "no path");
  }
  {
    Case c = makeCase(path);
    c.input.heading = std::nan("");
    EXPECT_EQ(reasonFor(c), "robot pose unknown (not finite)");
    c = makeCase(path);
    c.input.robot.x = INFINITY;
    EXPECT_EQ(reasonFor(c), "robot pose unknown (not finite)");
    c = makeCase(path);
    c.input.start = std::nan("");
    EXPECT_EQ(reasonFor(c), "robot pose unknown (not finite)");
  }
  {
    Case c = makeCase({{0, 0}, {std::nan(""), 0}, {0.2, 2}});
    EXPECT_EQ(reasonFor(c), "path has non-finite points");
  }
  EXPECT_EQ(reasonFor(makeCase(path, {})), "no lit area (fewer than 3 points)");
  EXPECT_EQ(reasonFor(makeCase(path, {{0.3, 0.4}, {1.3, 0.4}})), "no lit area (fewer than 3 points)");
  EXPECT_EQ(reasonFor(makeCase(path, {{0.3, 0}, {0.8, 0}, {1.3, 0}})), "lit area is not a simple polygon with area");
  // A bow tie: the edges (0.3,0.4)-(1.3,-0.4) and (1.3,0.4)-(0.3,-0.4) cross.
  EXPECT_EQ(reasonFor(makeCase(path, {{0.3, 0.4}, {1.3, -0.4}, {1.3, 0.4}, {0.3, -0.4}})),
            "lit area is not a simple polygon with area");
  // A repeated vertex folding back: (0.3,0.4) -> (1.3,0.4) -> (0.8,0.4) runs back along itself.
  EXPECT_EQ(reasonFor(makeCase(path, {{0.3, 0.4}, {1.3, 0.4}, {0.8, 0.4}, {1.3, -0.4}, {0.3, -0.4}})),
            "lit area is not a simple polygon with area");
  EXPECT_EQ(reasonFor(makeCase(path, {{0.3, 0.4}, {1.3, std::nan("")}, {1.3, -0.4}})),
            "lit area has non-finite or implausibly far points");
  EXPECT_EQ(reasonFor(makeCase(path, {{0.3, 0.4}, {1e300, 0.4}, {1.3, -0.4}})),
            "lit area has non-finite or implausibly far points");
  // 0.2 m x 0.2 m shrunk by 0.15 m on each side: nothing left.
  EXPECT_EQ(reasonFor(makeCase(path, {{0.3, 0.1}, {0.5, 0.1}, {0.5, -0.1}, {0.3, -0.1}})),
            "lit area too small for the margin");
  {
    Case c = makeCase(path);
    c.input.start = 2.2;  // at the destination
    EXPECT_EQ(reasonFor(c), "arrived (no path ahead)");
    EXPECT_TRUE(by_design);
  }
  {
    OffViewParameters zero;
    zero.arrow_length = 0.0;
    Case c = makeCase(path);
    EXPECT_EQ(cue.build(c.points, c.lengths, c.input, zero).reason, "cue sizes must be positive and finite");
  }
}

TEST(OffViewCue, RefusedInputResetsTheHysteresis)
{
  // Shown at fraction 0.2, then a NaN pose (None, reset), then fraction 1/3: a fresh decision
  // (hidden), not the kept cue.
  const auto lit = [](double a) { return std::vector<Vec2>{{a, 0.4}, {a + 1, 0.4}, {a + 1, -0.4}, {a, -0.4}}; };
  OffViewCue cue;
  Case c = makeCase({{0, 0}, {3, 0}}, lit(1.2));
  EXPECT_EQ(cue.build(c.points, c.lengths, c.input, OffViewParameters()).kind, OffViewKind::EdgeArrow);
  Case bad = c;
  bad.input.heading = std::nan("");
  EXPECT_EQ(cue.build(bad.points, bad.lengths, bad.input, OffViewParameters()).kind, OffViewKind::None);
  c.input.lit = lit(1.0);
  EXPECT_EQ(cue.build(c.points, c.lengths, c.input, OffViewParameters()).kind, OffViewKind::None);
}

TEST(OffViewCue, EitherOrientationAndFarOffCoordinatesGiveTheSameCue)
{
  // The edge-arrow case with the lit polygon counter-clockwise, then everything moved by
  // (1e5, -2e5) m: the same anchor, moved.
  Case c = makeCase({{0, 0}, {0.2, 0}, {0.2, 2}}, {{0.3, -0.4}, {1.3, -0.4}, {1.3, 0.4}, {0.3, 0.4}});
  OffViewCue cue;
  const OffViewResult r = cue.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(r.kind, OffViewKind::EdgeArrow);
  EXPECT_NEAR(r.anchor.x, 0.45, 1e-4);
  EXPECT_NEAR(r.anchor.y, 0.25, 1e-4);
  const Vec2 offset{1e5, -2e5};
  for (Vec2& p : c.points)
  {
    p = p + offset;
  }
  for (Vec2& p : c.input.lit)
  {
    p = p + offset;
  }
  c.input.robot = offset;
  OffViewCue far;
  const OffViewResult& moved = far.build(c.points, c.lengths, c.input, OffViewParameters());
  EXPECT_EQ(moved.kind, OffViewKind::EdgeArrow);
  EXPECT_NEAR(moved.anchor.x - offset.x, 0.45, 1e-4);
  EXPECT_NEAR(moved.anchor.y - offset.y, 0.25, 1e-4);
}
}  // namespace
}  // namespace rviz_projector
