// The planar motion maths of motion compensation (issue 14): integrateTwist, twistBetween,
// planarPose, mostHorizontalAxis, movePlanar, and the texts of a prediction. Expected values are
// closed forms computed here by hand (arcs of a unicycle, rotations built from quaternions).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

#include "motion_test_oracle.h"
#include "rviz_projector/core/motion_predictor.h"

using rviz_projector::describePrediction;
using rviz_projector::integrateTwist;
using rviz_projector::mostHorizontalAxis;
using rviz_projector::movePlanar;
using rviz_projector::planarPose;
using rviz_projector::PlanarPose;
using rviz_projector::PlanarTwist;
using rviz_projector::Prediction;
using rviz_projector::predictionStateName;
using rviz_projector::RigidTransform;
using rviz_projector::twistBetween;
using rviz_projector::Vec3;

namespace
{
using motion_oracle::aboutX;
using motion_oracle::aboutY;
using motion_oracle::aboutZ;
using motion_oracle::kDeg;
using motion_oracle::kOptical;
using motion_oracle::kPi;
using motion_oracle::pose;
using motion_oracle::Quat;

/// Angle a - b in (-pi, pi].
double angleDiff(double a, double b)
{
  double d = std::remainder(a - b, 2.0 * kPi);
  if (d <= -kPi)
  {
    d += 2.0 * kPi;
  }
  return d;
}

/// A projector's optical frame at `t`, heading `yaw` and looking `tilt` below the horizon.
RigidTransform projector(double yaw, double tilt, const Vec3& t)
{
  return pose(aboutZ(yaw) * aboutY(tilt) * kOptical, t);
}

void expectPlanar(const PlanarPose& p, double x, double y, double yaw, double tol = 1e-9)
{
  EXPECT_NEAR(p.x, x, tol);
  EXPECT_NEAR(p.y, y, tol);
  EXPECT_NEAR(angleDiff(p.yaw, yaw), 0.0, tol) << "yaw " << p.yaw << " expected " << yaw;
}

void expectTwist(const PlanarTwist& t, double vx, double vy, double wz, double tol = 1e-9)
{
  EXPECT_NEAR(t.vx, vx, tol);
  EXPECT_NEAR(t.vy, vy, tol);
  EXPECT_NEAR(t.wz, wz, tol);
}

void expectPose(const RigidTransform& a, const RigidTransform& b, double tol = 1e-9)
{
  EXPECT_NEAR(a.translation().x, b.translation().x, tol);
  EXPECT_NEAR(a.translation().y, b.translation().y, tol);
  EXPECT_NEAR(a.translation().z, b.translation().z, tol);
  for (int i = 0; i < 9; ++i)
  {
    EXPECT_NEAR(a.rotation()[i], b.rotation()[i], tol) << "rotation element " << i;
  }
}

/// Closed form of a unicycle with body twist (vx, vy, w), w != 0, from (x0, y0, yaw0) for t s.
PlanarPose arc(double x0, double y0, double yaw0, double vx, double vy, double w, double t)
{
  const double a = yaw0 + w * t;
  PlanarPose p;
  p.x = x0 + (vx * (std::sin(a) - std::sin(yaw0)) + vy * (std::cos(a) - std::cos(yaw0))) / w;
  p.y = y0 + (vx * (std::cos(yaw0) - std::cos(a)) + vy * (std::sin(a) - std::sin(yaw0))) / w;
  p.yaw = a;
  return p;
}
}  // namespace

// --- integrateTwist ----------------------------------------------------------------------------

TEST(IntegrateTwist, StraightAlongTheHeading)
{
  expectPlanar(integrateTwist({1.0, 2.0, 0.0}, {2.0, 0.0, 0.0}, 0.5), 2.0, 2.0, 0.0);
  expectPlanar(integrateTwist({1.0, 2.0, kPi / 2}, {2.0, 0.0, 0.0}, 0.5), 1.0, 3.0, kPi / 2);
  // Heading 30 deg: 1 m/s for 2 s.
  expectPlanar(integrateTwist({0.0, 0.0, kPi / 6}, {1.0, 0.0, 0.0}, 2.0), std::sqrt(3.0), 1.0, kPi / 6);
  // Backwards.
  expectPlanar(integrateTwist({0.0, 0.0, kPi}, {-0.5, 0.0, 0.0}, 2.0), 1.0, 0.0, kPi);
}

TEST(IntegrateTwist, SidewaysIsTheBodyYAxis)
{
  expectPlanar(integrateTwist({0.0, 0.0, 0.0}, {0.0, 0.5, 0.0}, 2.0), 0.0, 1.0, 0.0);
  expectPlanar(integrateTwist({0.0, 0.0, kPi / 2}, {0.0, 0.5, 0.0}, 2.0), -1.0, 0.0, kPi / 2);
  // Diagonal: forward and left at once, heading -90 deg.
  expectPlanar(integrateTwist({1.0, 1.0, -kPi / 2}, {1.0, 1.0, 0.0}, 1.0), 2.0, 0.0, -kPi / 2);
}

TEST(IntegrateTwist, PureRotationStaysInPlace)
{
  expectPlanar(integrateTwist({1.0, 1.0, 0.2}, {0.0, 0.0, 0.5}, 2.0), 1.0, 1.0, 1.2);
  expectPlanar(integrateTwist({-3.0, 4.0, 0.0}, {0.0, 0.0, -1.0}, 0.25), -3.0, 4.0, -0.25);
  // Across +-pi.
  expectPlanar(integrateTwist({0.0, 0.0, 3.0}, {0.0, 0.0, 0.5}, 1.0), 0.0, 0.0, 3.5);
}

TEST(IntegrateTwist, ArcIsTheClosedForm)
{
  // From the origin: x = v/w sin(w t), y = v/w (1 - cos(w t)).
  const double v = 0.7, w = 0.6, t = 1.3;
  const double r = v / w;
  expectPlanar(integrateTwist({0.0, 0.0, 0.0}, {v, 0.0, w}, t), r * std::sin(w * t), r * (1.0 - std::cos(w * t)),
               w * t);
  // A quarter circle of radius 2 to the right.
  expectPlanar(integrateTwist({0.0, 0.0, 0.0}, {kPi, 0.0, -kPi / 2}, 1.0), 2.0, -2.0, -kPi / 2);
  // A half circle of radius 1 (heading 0 -> pi).
  expectPlanar(integrateTwist({0.0, 0.0, 0.0}, {kPi, 0.0, kPi}, 1.0), 0.0, 2.0, kPi);
  // Anywhere, with a sideways component, over a long and a short time.
  for (double dt : {0.005, 0.05, 0.8, 3.0})
  {
    SCOPED_TRACE(dt);
    const PlanarPose e = arc(1.5, -2.0, 2.8, 0.9, -0.3, 1.7, dt);
    expectPlanar(integrateTwist({1.5, -2.0, 2.8}, {0.9, -0.3, 1.7}, dt), e.x, e.y, e.yaw);
    const PlanarPose f = arc(-0.4, 0.3, -1.0, 0.4, 0.2, -0.6, dt);
    expectPlanar(integrateTwist({-0.4, 0.3, -1.0}, {0.4, 0.2, -0.6}, dt), f.x, f.y, f.yaw);
  }
}

TEST(IntegrateTwist, NearlyStraightArcIsContinuous)
{
  // A tiny yaw rate must not divide by (almost) zero: the arc is then the straight line (the
  // sagitta of 1 m at 1e-9 rad/s is 5e-10 m).
  expectPlanar(integrateTwist({0.0, 0.0, 0.0}, {1.0, 0.0, 1e-9}, 1.0), 1.0, 0.0, 1e-9);
  expectPlanar(integrateTwist({0.0, 0.0, 0.0}, {1.0, 0.0, 1e-13}, 1.0), 1.0, 0.0, 0.0);
  expectPlanar(integrateTwist({0.0, 0.0, 0.0}, {1.0, 0.0, -1e-13}, 1.0), 1.0, 0.0, 0.0);
  // Second order: y = v w t^2 / 2 for small w t (1e-5 rad: error of the expansion ~1e-16 m).
  const PlanarPose p = integrateTwist({0.0, 0.0, 0.0}, {1.0, 0.0, 1e-5}, 1.0);
  EXPECT_NEAR(p.y, 0.5e-5, 1e-12);
}

TEST(IntegrateTwist, ZeroTimeIsTheStart)
{
  expectPlanar(integrateTwist({1.0, -2.0, 0.7}, {1.0, 0.5, 2.0}, 0.0), 1.0, -2.0, 0.7, 0.0);
}

// --- twistBetween ------------------------------------------------------------------------------

TEST(TwistBetween, InvertsTheClosedFormArc)
{
  const double v = 0.7, w = 0.6, t = 1.3;
  const double r = v / w;
  expectTwist(twistBetween({0.0, 0.0, 0.0}, {r * std::sin(w * t), r * (1.0 - std::cos(w * t)), w * t}, t), v, 0.0, w);
  expectTwist(twistBetween({0.0, 0.0, 0.0}, {2.0, -2.0, -kPi / 2}, 1.0), kPi, 0.0, -kPi / 2);
  const PlanarPose e = arc(1.5, -2.0, 2.8, 0.9, -0.3, 1.7, 0.05);
  expectTwist(twistBetween({1.5, -2.0, 2.8}, e, 0.05), 0.9, -0.3, 1.7, 1e-7);
}

TEST(TwistBetween, StraightSidewaysAndInPlace)
{
  expectTwist(twistBetween({1.0, 2.0, kPi / 2}, {1.0, 3.0, kPi / 2}, 0.5), 2.0, 0.0, 0.0);
  expectTwist(twistBetween({0.0, 0.0, kPi / 2}, {-1.0, 0.0, kPi / 2}, 2.0), 0.0, 0.5, 0.0);
  expectTwist(twistBetween({1.0, 1.0, 0.2}, {1.0, 1.0, 1.2}, 2.0), 0.0, 0.0, 0.5);
  expectTwist(twistBetween({1.0, 1.0, 0.2}, {1.0, 1.0, 0.2}, 0.01), 0.0, 0.0, 0.0);
}

TEST(TwistBetween, InvertsIntegrateTwist)
{
  const PlanarTwist twists[] = {{0.7, 0.0, 0.6}, {1.0, 0.0, 0.0}, {0.0, 0.0, 0.5}, {0.3, -0.8, -2.0}, {-1.2, 0.4, 2.9}};
  const PlanarPose starts[] = {{0.0, 0.0, 0.0}, {3.0, -1.0, 3.1}, {-2.0, 5.0, -3.1}};
  for (const PlanarTwist& tw : twists)
  {
    for (const PlanarPose& s : starts)
    {
      for (double dt : {0.005, 0.02, 0.1, 0.9})
      {
        SCOPED_TRACE(testing::Message() << "twist " << tw.vx << "," << tw.vy << "," << tw.wz << " dt " << dt);
        expectTwist(twistBetween(s, integrateTwist(s, tw, dt), dt), tw.vx, tw.vy, tw.wz, 1e-7);
      }
    }
  }
}

TEST(TwistBetween, HeadingChangeWrapsAcrossPi)
{
  // Turning left through +pi: the headings read 3.0 and 3.5 - 2 pi.
  const PlanarPose to = arc(0.0, 0.0, 3.0, 0.4, 0.0, 0.5, 1.0);
  expectTwist(twistBetween({0.0, 0.0, 3.0}, {to.x, to.y, 3.5 - 2.0 * kPi}, 1.0), 0.4, 0.0, 0.5, 1e-9);
  // Turning right through -pi, in place: -3.0 -> 3.0 is -(2 pi - 6) rad.
  expectTwist(twistBetween({1.0, 1.0, -3.0}, {1.0, 1.0, 3.0}, 0.1), 0.0, 0.0, (6.0 - 2.0 * kPi) / 0.1, 1e-9);
  // Headings given beyond (-pi, pi] are the same headings.
  expectTwist(twistBetween({1.0, 1.0, 0.1 + 4.0 * kPi}, {1.0, 1.0, 0.3 - 2.0 * kPi}, 0.1), 0.0, 0.0, 2.0, 1e-9);
}

TEST(TwistBetween, HalfTurnIsCounterClockwise)
{
  // A change of exactly -pi is taken as +pi (the range is (-pi, pi]).
  expectTwist(twistBetween({0.0, 0.0, 0.0}, {0.0, 0.0, -kPi}, 1.0), 0.0, 0.0, kPi, 1e-9);
  expectTwist(twistBetween({0.0, 0.0, 0.0}, {0.0, 0.0, kPi}, 2.0), 0.0, 0.0, kPi / 2, 1e-9);
}

// --- planarPose and mostHorizontalAxis -----------------------------------------------------------

TEST(PlanarPose, TiltedProjectorLookingDownAhead)
{
  // Optical frame heading 40 deg, looking 30 deg below the horizon. By hand:
  //   z (forward-down) = (cos40 cos30, sin40 cos30, -sin30): heading 40 deg;
  //   x (right)        = (sin40, -cos40, 0): horizontal, heading 40 - 90 deg;
  //   y (down-back)    = (-cos40 sin30, -sin40 sin30, -cos30): heading 40 - 180 deg.
  const double yaw = 40 * kDeg;
  const RigidTransform p = projector(yaw, 30 * kDeg, {1.0, -2.0, 1.5});
  // The hand-built rotation first (the oracle of the rest).
  EXPECT_NEAR(p.rotation()[2], std::cos(yaw) * std::cos(30 * kDeg), 1e-12);
  EXPECT_NEAR(p.rotation()[5], std::sin(yaw) * std::cos(30 * kDeg), 1e-12);
  EXPECT_NEAR(p.rotation()[8], -0.5, 1e-12);
  EXPECT_NEAR(p.rotation()[6], 0.0, 1e-12);

  expectPlanar(planarPose(p, 2), 1.0, -2.0, yaw, 1e-12);
  expectPlanar(planarPose(p, 0), 1.0, -2.0, yaw - kPi / 2, 1e-12);
  expectPlanar(planarPose(p, 1), 1.0, -2.0, yaw - kPi, 1e-12);
  EXPECT_EQ(mostHorizontalAxis(p), 0);
}

TEST(PlanarPose, BaseLinkAxes)
{
  const RigidTransform b = pose(aboutZ(-2.5), {3.0, 4.0, 0.1});
  expectPlanar(planarPose(b, 0), 3.0, 4.0, -2.5, 1e-12);
  expectPlanar(planarPose(b, 1), 3.0, 4.0, -2.5 + kPi / 2, 1e-12);
}

TEST(MostHorizontalAxis, TheAxisWithTheSmallestVerticalComponent)
{
  // Pitched 0.1 rad: x dips, y stays level.
  EXPECT_EQ(mostHorizontalAxis(pose(aboutZ(0.7) * aboutY(0.1), {})), 1);
  // Rolled 0.1 rad: y dips, x stays level.
  EXPECT_EQ(mostHorizontalAxis(pose(aboutZ(0.7) * aboutX(0.1), {})), 0);
  // Rolled 90 deg, then pitched 0.2 rad: z lies flat, x dips by sin 0.2, y points nearly up.
  EXPECT_EQ(mostHorizontalAxis(pose(aboutZ(-1.0) * aboutY(0.2) * aboutX(kPi / 2), {})), 2);
  // A projector looking straight down: x and y are both horizontal, never z.
  EXPECT_NE(mostHorizontalAxis(projector(0.3, kPi / 2, {0.0, 0.0, 2.0})), 2);
  // An optical frame looking 10 deg down (x horizontal, z nearly) and rolled 20 deg: x dips by
  // sin20 = 0.34, z by sin10 = 0.17, y is nearly vertical.
  EXPECT_EQ(mostHorizontalAxis(pose(aboutZ(0.5) * aboutY(10 * kDeg) * aboutX(20 * kDeg) * kOptical, {})), 2);
}

// --- movePlanar --------------------------------------------------------------------------------

TEST(MovePlanar, RotatesAboutTheVerticalAndKeepsHeightAndTilt)
{
  const RigidTransform p = pose(aboutZ(0.3) * aboutY(25 * kDeg) * aboutX(5 * kDeg) * kOptical, {1.0, 2.0, 1.5});
  const PlanarPose from{0.5, 0.5, 0.3};
  const PlanarPose to{1.5, -0.5, 1.1};
  const double turn = 0.8;
  // By hand: the point (1, 2) is (0.5, 1.5) from `from`; rotated by 0.8 rad and put at `to`.
  const double dx = 0.5, dy = 1.5;
  const Vec3 t{1.5 + std::cos(turn) * dx - std::sin(turn) * dy, -0.5 + std::sin(turn) * dx + std::cos(turn) * dy, 1.5};
  const RigidTransform expected = pose(aboutZ(turn) * aboutZ(0.3) * aboutY(25 * kDeg) * aboutX(5 * kDeg) * kOptical, t);
  const RigidTransform moved = movePlanar(p, from, to);
  expectPose(moved, expected, 1e-12);
  // Height and tilt (the vertical components of the body axes) unchanged.
  EXPECT_DOUBLE_EQ(moved.translation().z, 1.5);
  for (int i = 6; i < 9; ++i)
  {
    EXPECT_NEAR(moved.rotation()[i], p.rotation()[i], 1e-12);
  }
}

TEST(MovePlanar, SamePoseIsNoMotion)
{
  const RigidTransform p = projector(-2.0, 30 * kDeg, {-1.0, 0.5, 1.2});
  expectPose(movePlanar(p, {0.3, 0.4, 2.0}, {0.3, 0.4, 2.0}), p, 1e-12);
  // The planar pose of the body itself moved to `to` is `to`.
  const PlanarPose to{2.0, 3.0, 0.4};
  expectPlanar(planarPose(movePlanar(p, planarPose(p, 0), to), 0), to.x, to.y, to.yaw, 1e-12);
}

TEST(MovePlanar, HeadingsDifferingByTwoPiAreTheSameHeading)
{
  const RigidTransform p = projector(1.0, 30 * kDeg, {0.0, 0.0, 1.0});
  const RigidTransform a = movePlanar(p, {0.0, 0.0, 3.0}, {1.0, 0.0, 3.2});
  const RigidTransform b = movePlanar(p, {0.0, 0.0, 3.0}, {1.0, 0.0, 3.2 - 2.0 * kPi});
  expectPose(a, b, 1e-12);
}

// --- texts -------------------------------------------------------------------------------------

TEST(DescribePrediction, StateNamesAndTexts)
{
  const struct
  {
    Prediction::State state;
    const char* name;
  } states[] = {{Prediction::Predicted, "Predicted"}, {Prediction::Limited, "Limited"},
                {Prediction::Stopped, "Stopped"},     {Prediction::Collecting, "Collecting"},
                {Prediction::Jump, "Jump"},           {Prediction::Gap, "Gap"},
                {Prediction::TooFast, "TooFast"},     {Prediction::NoPose, "NoPose"}};
  std::set<std::string> texts;
  for (const auto& s : states)
  {
    EXPECT_STREQ(predictionStateName(s.state), s.name);
    Prediction p;
    p.state = s.state;
    p.wanted = 0.041;
    if (p.extrapolated())
    {
      p.horizon = 0.041;
      p.twist = {0.98, 0.0, 0.5};
      p.speed = 0.98;
    }
    const std::string text = describePrediction(p);
    EXPECT_FALSE(text.empty()) << s.name;
    texts.insert(text);
  }
  // A different text for each state (a status line must tell them apart).
  EXPECT_EQ(texts.size(), 8u);
}

TEST(DescribePrediction, PredictedSaysHowFarAhead)
{
  Prediction p;
  p.state = Prediction::Predicted;
  p.horizon = p.wanted = 0.041;
  p.twist = {0.98, 0.0, 0.5};
  p.speed = 0.98;
  const std::string text = describePrediction(p);
  EXPECT_NE(text.find("ms"), std::string::npos) << text;
  EXPECT_NE(text.find("41"), std::string::npos) << text;
  // Junk values give a text too (the status line shows whatever it gets).
  p.horizon = p.speed = std::nan("");
  p.twist.wz = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(describePrediction(p).empty());
}
