// Exact mode of PathSpacer: arrows by arc length, anchored at the destination.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/disc_outline.h"
#include "rviz_projector/core/path_spacer.h"

using rviz_projector::Arrow;
using rviz_projector::ArrowOutline;
using rviz_projector::PathSpacer;
using rviz_projector::SpacedPath;
using rviz_projector::SpacingParameters;
using rviz_projector::Vec2;

namespace
{
SpacingParameters exactParameters()
{
  SpacingParameters p;
  p.spacing = 0.3;
  p.arrow.shaft_length = 0.1;
  p.arrow.head_length = 0.08;
  p.arrow.shaft_diameter = 0.05;
  p.arrow.head_diameter = 0.12;
  p.circle_diameter = 0.2;
  p.destination_gap = 0.05;
  return p;
}

/// Straight path along +x from 0 to `length`, with pose steps cycling through `steps`.
std::vector<Vec2> unevenLine(double length, const std::vector<double>& steps)
{
  std::vector<Vec2> path{{0.0, 0.0}};
  double x = 0.0;
  for (std::size_t i = 0; x < length; ++i)
  {
    x = std::min(length, x + steps[i % steps.size()]);
    path.push_back({x, 0.0});
  }
  return path;
}

/// Circle arc of radius r centred at the origin from angle 0 to `angle`, unevenly sampled.
std::vector<Vec2> unevenArc(double r, double angle, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> step(0.005, 0.12);
  std::vector<Vec2> path;
  for (double a = 0.0; a < angle; a += step(rng) / r)
  {
    path.push_back({r * std::cos(a), r * std::sin(a)});
  }
  path.push_back({r * std::cos(angle), r * std::sin(angle)});
  return path;
}

/// The point at arc length `s` from the last point of `path`, by a plain walk (a test oracle).
Vec2 pointFromEnd(const std::vector<Vec2>& path, double s)
{
  for (std::size_t i = path.size() - 1; i > 0; --i)
  {
    const Vec2 a = path[i], b = path[i - 1];
    const double length = std::hypot(b.x - a.x, b.y - a.y);
    if (s <= length)
    {
      const double f = length > 0.0 ? s / length : 0.0;
      return {a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f};
    }
    s -= length;
  }
  return path.front();
}

/// Angle (arc length / r) of a point on the circle of radius r, measured from angle 0.
double arcAngle(const Vec2& p) { return std::atan2(p.y, p.x); }
}  // namespace

TEST(PathSpacerExact, StraightLineTipsAreSpacedFromTheDestination)
{
  PathSpacer spacer(exactParameters());
  const SpacedPath& out = spacer.space(unevenLine(3.0, {0.05, 0.013, 0.11, 0.07}));
  ASSERT_TRUE(out.has_destination);
  EXPECT_DOUBLE_EQ(out.destination.x, 3.0);
  // First tip at r + gap = 0.15 back from x = 3; tails 0.18 further; tips every 0.3 m.
  // Arrows fit while 0.15 + 0.3 k + 0.18 <= 3  ->  k <= 8.9  ->  9 arrows.
  ASSERT_EQ(out.arrows.size(), 9u);
  for (std::size_t k = 0; k < out.arrows.size(); ++k)
  {
    EXPECT_NEAR(out.arrows[k].tip.x, 3.0 - 0.15 - 0.3 * k, 1e-9) << k;
    EXPECT_NEAR(out.arrows[k].tail.x, 3.0 - 0.33 - 0.3 * k, 1e-9) << k;
    EXPECT_NEAR(out.arrows[k].tip.y, 0.0, 1e-12);
  }
  EXPECT_EQ(out.dropped_points, 0u);
  EXPECT_NEAR(out.path_length, 3.0, 1e-12);
}

TEST(PathSpacerExact, SpacingIsIndependentOfPoseSpacingOnACurve)
{
  const double r = 1.5;
  const double angle = 2.5;  // 3.75 m of arc
  for (unsigned seed = 1; seed <= 5; ++seed)
  {
    PathSpacer spacer(exactParameters());
    // Dense uneven sampling approximates the arc: measure arc length along the polyline itself,
    // which is what the spacing is defined on, by re-walking the input.
    const std::vector<Vec2> path = unevenArc(r, angle, seed);
    const SpacedPath& out = spacer.space(path);
    ASSERT_GE(out.arrows.size(), 10u);
    // Arc length from the destination of a point on the polyline.
    auto arcFromEnd = [&path](const Vec2& p) {
      double s = 0.0;
      double best = std::numeric_limits<double>::infinity();
      double best_s = 0.0;
      for (std::size_t i = path.size() - 1; i > 0; --i)
      {
        const Vec2 a = path[i], b = path[i - 1];
        const double l = rviz_projector::distance(a, b);
        const double t = l > 0 ? std::max(0.0, std::min(1.0, rviz_projector::dot(p - a, b - a) / (l * l))) : 0.0;
        const double d = rviz_projector::distance(a + (b - a) * t, p);
        if (d < best)
        {
          best = d;
          best_s = s + t * l;
        }
        s += l;
      }
      return best_s;
    };
    for (std::size_t k = 0; k < out.arrows.size(); ++k)
    {
      EXPECT_NEAR(arcFromEnd(out.arrows[k].tip), 0.15 + 0.3 * k, 1e-6) << "seed " << seed << " arrow " << k;
      EXPECT_NEAR(arcFromEnd(out.arrows[k].tail), 0.33 + 0.3 * k, 1e-6) << "seed " << seed << " arrow " << k;
      // Points lie on the arc (up to the polyline's chord error).
      EXPECT_NEAR(rviz_projector::norm(out.arrows[k].tip), r, 2e-3);
    }
    // Tip-to-tip arc spacing, measured as angle on the circle, is about 0.3 / r.
    EXPECT_NEAR(arcAngle(out.arrows[0].tip) - arcAngle(out.arrows[1].tip), 0.3 / r, 2e-3);
  }
}

TEST(PathSpacerExact, TrimmingTheStartKeepsEveryRemainingArrowInPlace)
{
  const std::vector<Vec2> full = unevenArc(2.0, 2.0, 7);
  PathSpacer spacer(exactParameters());
  const std::vector<Arrow> before = spacer.space(full).arrows;
  ASSERT_GT(before.size(), 5u);
  for (std::size_t cut = 1; cut < full.size() / 2; cut += 3)
  {
    std::vector<Vec2> trimmed(full.begin() + static_cast<std::ptrdiff_t>(cut), full.end());
    // The robot's own pose, mid-segment, starts the new plan (as a planner emits it).
    const Vec2 robot = full[cut - 1] + (full[cut] - full[cut - 1]) * 0.5;
    trimmed.insert(trimmed.begin(), robot);
    const SpacedPath& after = spacer.space(trimmed);
    ASSERT_LE(after.arrows.size(), before.size());
    ASSERT_GE(after.arrows.size() + 2, before.size() - cut / 3);  // only arrows near the start go
    for (std::size_t k = 0; k < after.arrows.size(); ++k)
    {
      EXPECT_NEAR(after.arrows[k].tip.x, before[k].tip.x, 1e-9);
      EXPECT_NEAR(after.arrows[k].tip.y, before[k].tip.y, 1e-9);
      EXPECT_NEAR(after.arrows[k].tail.x, before[k].tail.x, 1e-9);
      EXPECT_NEAR(after.arrows[k].tail.y, before[k].tail.y, 1e-9);
    }
  }
}

TEST(PathSpacerExact, ArrowsNeverOverlapTheDestinationCircle)
{
  SpacingParameters p = exactParameters();
  p.destination_gap = 0.0;  // worst case: the first tip is exactly on the circle's edge
  // A tight spiral-like curl that comes back around the goal: chords cut corners.
  const std::vector<Vec2> path = unevenArc(0.4, 5.5, 3);
  for (double diameter : {0.05, 0.2, 0.6, 1.2})
  {
    for (double head_diameter : {0.0, 0.12, 0.5})  // narrower than the shaft, and far wider
    {
      p.circle_diameter = diameter;
      p.arrow.head_diameter = head_diameter;
      PathSpacer spacer(p);
      const SpacedPath& out = spacer.space(path);
      // (A 1.2 m circle round a 0.8 m wide curl leaves no room for a 0.5 m wide head.)
      const bool room = diameter < 1.0 || head_diameter < 0.5;
      ASSERT_EQ(out.arrows.empty(), !room) << diameter << ", head diameter " << head_diameter;
      for (const Arrow& a : out.arrows)
      {
        const ArrowOutline outline(a, p.arrow);
        EXPECT_GE(outline.distanceTo(out.destination), 0.5 * diameter - 1e-9)
            << "diameter " << diameter << ", head diameter " << head_diameter;
      }
    }
  }
}

TEST(PathSpacerExact, ExactlyTheArrowsOverTheCircleAreLeftOut)
{
  // Random walks that wander round their destination: every arrow position the spacing gives is
  // kept if and only if its outline stays off the circle (an oracle placing them independently).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> turn(-1.2, 1.2), step(0.01, 0.15), size(0.02, 0.6);
  std::size_t dropped_in_total = 0, kept_in_total = 0;
  for (int trial = 0; trial < 200; ++trial)
  {
    SpacingParameters p = exactParameters();
    p.destination_gap = 0.0;
    p.spacing = size(rng);
    p.circle_diameter = 2.0 * size(rng);
    p.arrow.shaft_length = size(rng);
    p.arrow.head_length = 0.5 * size(rng);
    p.arrow.shaft_diameter = 0.3 * size(rng);
    p.arrow.head_diameter = size(rng);
    std::vector<Vec2> path{{0.0, 0.0}};
    double heading = 0.0;
    for (int i = 0; i < 60; ++i)
    {
      heading += turn(rng);
      const double d = step(rng);
      path.push_back({path.back().x + d * std::cos(heading), path.back().y + d * std::sin(heading)});
    }
    PathSpacer spacer(p);
    const SpacedPath& out = spacer.space(path);
    std::vector<Arrow> expected;
    for (int k = 0;; ++k)
    {
      const double tip = 0.5 * p.circle_diameter + k * p.spacing;
      if (tip + p.arrow.length() > out.path_length)
      {
        break;
      }
      const Arrow arrow{pointFromEnd(path, tip + p.arrow.length()), pointFromEnd(path, tip)};
      if (ArrowOutline(arrow, p.arrow).distanceTo(path.back()) >= 0.5 * p.circle_diameter)
      {
        expected.push_back(arrow);
      }
      else
      {
        ++dropped_in_total;
      }
    }
    ASSERT_EQ(out.arrows.size(), expected.size()) << "trial " << trial;
    for (std::size_t k = 0; k < expected.size(); ++k)
    {
      EXPECT_NEAR(out.arrows[k].tip.x, expected[k].tip.x, 1e-9) << "trial " << trial << ", arrow " << k;
      EXPECT_NEAR(out.arrows[k].tip.y, expected[k].tip.y, 1e-9) << "trial " << trial << ", arrow " << k;
    }
    kept_in_total += expected.size();
  }
  // The walks really do bring arrows over their circles, and leave others clear of it.
  EXPECT_GT(dropped_in_total, 50u);
  EXPECT_GT(kept_in_total, 500u);
}

TEST(PathSpacerExact, ArrowOutlineDistance)
{
  rviz_projector::ArrowDimensions d;
  d.head_length = 0.1;
  d.shaft_diameter = 0.1;
  d.head_diameter = 0.2;
  const ArrowOutline outline(Arrow{{0, 0}, {1, 0}}, d);
  EXPECT_DOUBLE_EQ(outline.distanceTo({0.5, 0.0}), 0.0);  // inside the shaft
  EXPECT_NEAR(outline.distanceTo({0.5, 0.3}), 0.25, 1e-12);
  EXPECT_NEAR(outline.distanceTo({-0.5, 0.0}), 0.5, 1e-12);
  EXPECT_NEAR(outline.distanceTo({1.5, 0.0}), 0.5, 1e-12);
}

TEST(PathSpacerExact, OnlyArrowsThatFitEntirelyAreDrawn)
{
  SpacingParameters p = exactParameters();
  PathSpacer spacer(p);
  // 0.15 + 0.18 = 0.33 m needed for one arrow.
  EXPECT_EQ(spacer.space({{0, 0}, {0.3299, 0}}).arrows.size(), 0u);
  EXPECT_EQ(spacer.space({{0, 0}, {0.33, 0}}).arrows.size(), 1u);
  EXPECT_EQ(spacer.space({{0, 0}, {0.6299, 0}}).arrows.size(), 1u);
  EXPECT_EQ(spacer.space({{0, 0}, {0.63, 0}}).arrows.size(), 2u);
}

TEST(PathSpacerExact, DegenerateInputs)
{
  PathSpacer spacer(exactParameters());
  const SpacedPath& empty = spacer.space({});
  EXPECT_FALSE(empty.has_destination);
  EXPECT_TRUE(empty.arrows.empty());

  const SpacedPath& one = spacer.space({{1.0, 2.0}});
  EXPECT_TRUE(one.has_destination);
  EXPECT_DOUBLE_EQ(one.destination.y, 2.0);
  EXPECT_TRUE(one.arrows.empty());

  const SpacedPath& two = spacer.space({{0.0, 0.0}, {1.0, 0.0}});
  EXPECT_EQ(two.arrows.size(), 3u);  // 0.33, 0.63, 0.93 <= 1

  const SpacedPath& same = spacer.space(std::vector<Vec2>(50, Vec2{0.5, 0.5}));
  EXPECT_TRUE(same.has_destination);
  EXPECT_TRUE(same.arrows.empty());
  EXPECT_EQ(same.path_length, 0.0);

  // Repeated poses (zero-length segments) change nothing.
  const SpacedPath& repeated = spacer.space({{0, 0}, {0, 0}, {0.5, 0}, {0.5, 0}, {0.5, 0}, {1.0, 0}, {1.0, 0}});
  ASSERT_EQ(repeated.arrows.size(), 3u);
  EXPECT_NEAR(repeated.arrows[1].tip.x, 1.0 - 0.45, 1e-12);
}

TEST(PathSpacerExact, NonFinitePointsAreDroppedAndCounted)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  PathSpacer spacer(exactParameters());
  const SpacedPath& out = spacer.space({{0, 0}, {nan, 0}, {0.5, inf}, {0.5, 0}, {-inf, nan}, {1.0, 0}});
  EXPECT_EQ(out.dropped_points, 3u);
  EXPECT_EQ(out.arrows.size(), 3u);
  for (const Arrow& a : out.arrows)
  {
    EXPECT_TRUE(rviz_projector::isFinite(a.tip));
    EXPECT_TRUE(rviz_projector::isFinite(a.tail));
  }
  const SpacedPath& all_bad = spacer.space({{nan, nan}, {inf, 0}});
  EXPECT_EQ(all_bad.dropped_points, 2u);
  EXPECT_FALSE(all_bad.has_destination);

  // A non-finite destination: the last finite point becomes the destination.
  const SpacedPath& bad_end = spacer.space({{0, 0}, {1.0, 0}, {nan, 1.0}});
  EXPECT_EQ(bad_end.dropped_points, 1u);
  ASSERT_TRUE(bad_end.has_destination);
  EXPECT_DOUBLE_EQ(bad_end.destination.x, 1.0);
  EXPECT_EQ(bad_end.arrows.size(), 3u);
  // One pose, and it is not finite: nothing at all.
  const SpacedPath& one_bad = spacer.space({{inf, 2.0}});
  EXPECT_EQ(one_bad.dropped_points, 1u);
  EXPECT_FALSE(one_bad.has_destination);
}

TEST(PathSpacerExact, MillionPosesAndArrowCap)
{
  std::vector<Vec2> path(1000000);
  for (std::size_t i = 0; i < path.size(); ++i)
  {
    path[i] = {0.001 * static_cast<double>(i), 0.0};
  }
  PathSpacer spacer(exactParameters());
  const SpacedPath& out = spacer.space(path);
  // Length 999.999 m: (999.999 - 0.33) / 0.3 + 1 = 3333 arrows.
  EXPECT_EQ(out.arrows.size(), 3333u);
  EXPECT_FALSE(out.truncated);

  SpacingParameters p = exactParameters();
  p.spacing = 0.0;  // clamped to kMinSpacing
  p.max_arrows = 1000;
  spacer.setParameters(p);
  EXPECT_DOUBLE_EQ(spacer.parameters().spacing, SpacingParameters::kMinSpacing);
  const SpacedPath& capped = spacer.space({{0, 0}, {1e9, 0}});
  EXPECT_EQ(capped.arrows.size(), 1000u);
  EXPECT_TRUE(capped.truncated);
}

TEST(PathSpacerExact, NonsenseParametersAreSanitised)
{
  SpacingParameters p = exactParameters();
  p.spacing = std::numeric_limits<double>::quiet_NaN();
  p.arrow.shaft_length = -1.0;
  p.circle_diameter = -std::numeric_limits<double>::infinity();
  PathSpacer spacer(p);
  EXPECT_DOUBLE_EQ(spacer.parameters().spacing, SpacingParameters().spacing);
  EXPECT_DOUBLE_EQ(spacer.parameters().arrow.shaft_length, 0.0);
  EXPECT_DOUBLE_EQ(spacer.parameters().circle_diameter, SpacingParameters().circle_diameter);
  EXPECT_FALSE(spacer.space({{0, 0}, {5, 0}}).arrows.empty());
}
