// Projector mount convention (issue 12): projector.launch's x y z roll pitch yaw (tf2's fixed-axis
// R = Rz(yaw) Ry(pitch) Rx(roll)) then the body -> optical rotation; hand-computed axes, a
// matrix-product oracle, and the round trip mount -> optical pose -> mount.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "mount_test_oracle.h"
#include "rviz_projector/core/projector_mount.h"

using rviz_projector::mountOfOpticalPose;
using rviz_projector::opticalPoseOfMount;
using rviz_projector::ProjectorMount;
using rviz_projector::RigidTransform;
using rviz_projector::Vec3;

namespace
{
using mount_oracle::kDeg;
using mount_oracle::Mat;
using mount_oracle::mul;

/// Oracle: the textbook elementary rotations multiplied out, then the optical axes (x right, y down,
/// z forward) as body axes: optical x = -body y, optical y = -body z, optical z = body x.
Mat oracleRotation(const ProjectorMount& m)
{
  const double cr = std::cos(m.roll), sr = std::sin(m.roll), cp = std::cos(m.pitch), sp = std::sin(m.pitch);
  const double cy = std::cos(m.yaw), sy = std::sin(m.yaw);
  const Mat rx{{{1, 0, 0}, {0, cr, -sr}, {0, sr, cr}}};
  const Mat ry{{{cp, 0, sp}, {0, 1, 0}, {-sp, 0, cp}}};
  const Mat rz{{{cy, -sy, 0}, {sy, cy, 0}, {0, 0, 1}}};
  const Mat body_to_optical{{{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}}};  // columns: optical x, y, z in body
  return mul(mul(mul(rz, ry), rx), body_to_optical);
}

void expectAxis(const RigidTransform& t, const Vec3& optical_axis, const Vec3& expected_in_parent, const char* what)
{
  const Vec3 a = t.rotate(optical_axis);
  EXPECT_NEAR(a.x, expected_in_parent.x, 1e-12) << what;
  EXPECT_NEAR(a.y, expected_in_parent.y, 1e-12) << what;
  EXPECT_NEAR(a.z, expected_in_parent.z, 1e-12) << what;
}

double rotationDistance(const RigidTransform& a, const RigidTransform& b)
{
  double d = 0.0;
  for (int i = 0; i < 9; ++i)
  {
    d = std::max(d, std::fabs(a.rotation()[i] - b.rotation()[i]));
  }
  return d;
}

double angleDifference(double a, double b)
{
  return std::fabs(std::remainder(a - b, 2 * M_PI));
}
}  // namespace

TEST(ProjectorMount, LevelMountLooksAlongParentX)
{
  const RigidTransform t = opticalPoseOfMount({0.1, -0.2, 1.2, 0, 0, 0});
  expectAxis(t, {0, 0, 1}, {1, 0, 0}, "optical z = parent +x");
  expectAxis(t, {1, 0, 0}, {0, -1, 0}, "optical x = parent -y");
  expectAxis(t, {0, 1, 0}, {0, 0, -1}, "optical y = parent -z");
  EXPECT_EQ(t.translation().x, 0.1);
  EXPECT_EQ(t.translation().y, -0.2);
  EXPECT_EQ(t.translation().z, 1.2);
}

TEST(ProjectorMount, PositivePitchTiltsTheBeamDown)
{
  const double p = 30 * kDeg;
  const RigidTransform t = opticalPoseOfMount({0, 0, 1, 0, p, 0});
  expectAxis(t, {0, 0, 1}, {std::cos(p), 0, -std::sin(p)}, "beam down and forward");
  expectAxis(t, {1, 0, 0}, {0, -1, 0}, "optical x unchanged by pitch");
  expectAxis(t, {0, 1, 0}, {-std::sin(p), 0, -std::cos(p)}, "optical y");
}

TEST(ProjectorMount, YawTurnsLeftRollTurnsAboutTheBeam)
{
  expectAxis(opticalPoseOfMount({0, 0, 0, 0, 0, 90 * kDeg}), {0, 0, 1}, {0, 1, 0}, "yaw 90: beam along +y");
  expectAxis(opticalPoseOfMount({0, 0, 0, 0, 0, 90 * kDeg}), {1, 0, 0}, {1, 0, 0}, "yaw 90: optical x = +x");
  // Roll 90 about the body x axis: body y -> parent +z, so the image's right (optical x = -body y)
  // points down, and its down (optical y = -body z) points to parent +y.
  expectAxis(opticalPoseOfMount({0, 0, 0, 90 * kDeg, 0, 0}), {1, 0, 0}, {0, 0, -1}, "roll 90: optical x");
  expectAxis(opticalPoseOfMount({0, 0, 0, 90 * kDeg, 0, 0}), {0, 1, 0}, {0, 1, 0}, "roll 90: optical y");
  // Order matters: pitch then yaw about fixed axes = beam tilted down, then turned left.
  const double p = 40 * kDeg, y = 25 * kDeg;
  expectAxis(opticalPoseOfMount({0, 0, 0, 0, p, y}), {0, 0, 1},
             {std::cos(y) * std::cos(p), std::sin(y) * std::cos(p), -std::sin(p)}, "pitch then yaw");
}

TEST(ProjectorMount, MatchesTheMatrixProductOracle)
{
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_real_distribution<double> half(-M_PI / 2, M_PI / 2);
  for (int i = 0; i < 1000; ++i)
  {
    const ProjectorMount m{0.3, -0.1, 1.0, angle(rng), half(rng), angle(rng)};
    const Mat o = oracleRotation(m);
    const RigidTransform t = opticalPoseOfMount(m);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(t.rotation()[3 * r + c], o[r][c], 1e-12) << "mount " << i;
  }
}

TEST(ProjectorMount, RoundTripIncludingGimbalLockAndWrapAround)
{
  std::mt19937 rng(1212);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_real_distribution<double> half(-M_PI / 2, M_PI / 2);
  std::uniform_real_distribution<double> pos(-2.0, 2.0);
  std::vector<ProjectorMount> mounts;
  for (int i = 0; i < 2000; ++i)
  {
    mounts.push_back({pos(rng), pos(rng), pos(rng), angle(rng), half(rng), angle(rng)});
  }
  for (double pitch : {89.9 * kDeg, -89.9 * kDeg, 89.999 * kDeg, 0.0})
    for (double r : {-M_PI, M_PI, 0.3, -179.9 * kDeg})
      for (double y : {-M_PI, M_PI, -2.0, 179.9 * kDeg})
        mounts.push_back({0.1, 0.2, 1.3, r, pitch, y});
  for (const ProjectorMount& m : mounts)
  {
    const ProjectorMount back = mountOfOpticalPose(opticalPoseOfMount(m));
    EXPECT_EQ(back.x, m.x);
    EXPECT_EQ(back.y, m.y);
    EXPECT_EQ(back.z, m.z);
    EXPECT_GT(back.roll, -M_PI);
    EXPECT_LE(back.roll, M_PI);
    EXPECT_GT(back.yaw, -M_PI);
    EXPECT_LE(back.yaw, M_PI);
    EXPECT_NEAR(back.pitch, m.pitch, 1e-8);
    // Near gimbal lock the angles are ill-conditioned (cos(pitch) ~ 2e-5 at 89.999 degrees); the
    // pose is what must round-trip, and the angles too wherever they are defined.
    const double tol = 1e-9 / std::max(1e-6, std::cos(m.pitch));
    EXPECT_LT(angleDifference(back.roll, m.roll), tol) << m.roll << " " << m.pitch << " " << m.yaw;
    EXPECT_LT(angleDifference(back.yaw, m.yaw), tol) << m.roll << " " << m.pitch << " " << m.yaw;
    EXPECT_LT(rotationDistance(opticalPoseOfMount(back), opticalPoseOfMount(m)), 1e-12);
  }
}

TEST(ProjectorMount, ExactGimbalLockKeepsThePose)
{
  for (double pitch : {M_PI / 2, -M_PI / 2})
  {
    const ProjectorMount m{0, 0, 1, 0.4, pitch, -1.1};
    const ProjectorMount back = mountOfOpticalPose(opticalPoseOfMount(m));
    EXPECT_NEAR(back.pitch, pitch, 1e-7);
    EXPECT_LT(rotationDistance(opticalPoseOfMount(back), opticalPoseOfMount(m)), 1e-7);
  }
}
