// Mount solver with fit_distortion (issue 24): k1, k2 from tape-measured crosshairs. The floor
// points come from OpenCV directly (distortion_oracle.h) through a true distorting lens: 25
// crosshairs over the image pin k1; 9 measured to 3 mm cannot, and the solver says so; the
// refusals of too few points, uncovered corners and fitting intrinsics and distortion together.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "distortion_oracle.h"
#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"

using distortion_oracle::Lens;
using mount_oracle::kDeg;
using mount_oracle::Mount;
using rviz_projector::FloorPoint;
using rviz_projector::MountSolution;
using rviz_projector::MountSolverOptions;
using rviz_projector::solveMount;

namespace
{
const Mount kDemo{0.15, 0.0, 1.2, 0.0, 0.876, 0.0};

/// The rows x cols crosshairs' floor points under the true lens and mount (exact).
std::vector<FloorPoint> crosshairs(const Lens& lens, const Mount& m, int rows, int cols)
{
  std::vector<FloorPoint> points;
  for (const rviz_projector::Crosshair& c : rviz_projector::crosshairPattern(1280, 800, rows, cols))
  {
    rviz_projector::Vec3 w;
    EXPECT_TRUE(distortion_oracle::floorOf(lens, m, c.pixel, w)) << c.id;
    points.push_back({c.id, c.pixel, w});
  }
  return points;
}

MountSolverOptions distortionOptions(double tape_error)
{
  MountSolverOptions options = MountSolverOptions::forTapeError(tape_error);
  options.fit_distortion = true;
  return options;
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

Lens lensOf(const MountSolution& s)
{
  Lens lens;
  if (!s.distortion.none())
  {
    lens.d = s.distortion.coefficients();
  }
  return lens;
}
}  // namespace

TEST(MountSolverDistortion, TwentyFiveExactCrosshairsRecoverK1K2AndTheMount)
{
  const Lens truth = distortion_oracle::lensWith(-0.2, 0.05);
  const MountSolution s = solveMount(truth.model(), crosshairs(truth, kDemo, 5, 5), distortionOptions(0.001));
  ASSERT_TRUE(s.ok) << s.error;
  const Lens fitted = lensOf(s);
  ASSERT_EQ(5u, fitted.d.size());
  EXPECT_NEAR(-0.2, fitted.d[0], 1e-5);
  EXPECT_NEAR(0.05, fitted.d[1], 1e-4);
  EXPECT_EQ(0.0, fitted.d[2]);
  EXPECT_EQ(0.0, fitted.d[4]);
  EXPECT_GT(s.distortion_stddev[0], 0.0);
  const Mount m = mount_oracle::fromSolution(s.mount);
  EXPECT_LT(distortion_oracle::positionError(m, kDemo), 1e-5);
  EXPECT_LT(mount_oracle::rotationAngle(m, kDemo), 1e-5);
  EXPECT_LT(s.rms_mm, 0.01);
  const distortion_oracle::FloorError e = distortion_oracle::floorError(truth, kDemo, fitted, m);
  EXPECT_LT(e.max_mm, 0.1);
  EXPECT_FALSE(s.expected.empty());
}

TEST(MountSolverDistortion, TwentyFiveCrosshairsWithOneMillimetreNoisePinK1)
{
  const Lens truth = distortion_oracle::lensWith(-0.1, 0.0);
  std::vector<FloorPoint> points = crosshairs(truth, kDemo, 5, 5);
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.001);
  for (FloorPoint& p : points)
  {
    p.world.x += noise(random), p.world.y += noise(random);
  }
  const MountSolution s = solveMount(truth.model(), points, distortionOptions(0.001));
  ASSERT_TRUE(s.ok) << s.error;
  std::cout << "[ info ] k1 " << s.distortion.coefficients()[0] << " +- " << s.distortion_stddev[0] << ", k2 "
            << s.distortion.coefficients()[1] << " +- " << s.distortion_stddev[1] << "\n";
  EXPECT_NEAR(-0.1, s.distortion.coefficients()[0], 4 * s.distortion_stddev[0]);
  EXPECT_LT(s.distortion_stddev[0], 0.05);
  const Lens fitted = lensOf(s);
  const distortion_oracle::FloorError e =
      distortion_oracle::floorError(truth, kDemo, fitted, mount_oracle::fromSolution(s.mount));
  EXPECT_LT(e.median_mm, 3.0);
}

TEST(MountSolverDistortion, NineCrosshairsMeasuredToThreeMillimetresCannotPinK1)
{
  const Lens truth = distortion_oracle::lensWith(-0.1, 0.0);
  const MountSolution s = solveMount(truth.model(), crosshairs(truth, kDemo, 3, 3), distortionOptions(0.003));
  EXPECT_FALSE(s.ok);
  EXPECT_TRUE(contains(s.error, "cannot pin the distortion")) << s.error;
  std::cout << "[ info ] " << s.error << "\n";
  EXPECT_TRUE(contains(s.error, "--rows 5 --cols 5")) << s.error;
  // Without fit_distortion the same points solve (the pinhole's error is in the residuals).
  EXPECT_TRUE(solveMount(truth.model(), crosshairs(truth, kDemo, 3, 3), MountSolverOptions::forTapeError(0.003)).ok);
}

TEST(MountSolverDistortion, RefusesTooFewPointsAndUncoveredCorners)
{
  const Lens truth = distortion_oracle::lensWith(-0.1, 0.0);
  const std::vector<FloorPoint> grid = crosshairs(truth, kDemo, 2, 3);
  const MountSolution few = solveMount(truth.model(), grid, distortionOptions(0.001));
  EXPECT_FALSE(few.ok);
  EXPECT_TRUE(contains(few.error, "at least 8 points")) << few.error;

  // 5 x 5 without the top-left crosshair and its neighbours.
  std::vector<FloorPoint> points;
  for (const FloorPoint& p : crosshairs(truth, kDemo, 5, 5))
  {
    if (!(p.pixel.x < 400 && p.pixel.y < 300))
    {
      points.push_back(p);
    }
  }
  const MountSolution corner = solveMount(truth.model(), points, distortionOptions(0.001));
  EXPECT_FALSE(corner.ok);
  EXPECT_TRUE(contains(corner.error, "none near the top left corner")) << corner.error;
}

TEST(MountSolverDistortion, NotTogetherWithIntrinsics)
{
  const Lens truth = distortion_oracle::lensWith(-0.1, 0.0);
  MountSolverOptions options = distortionOptions(0.001);
  options.fit_intrinsics = true;
  const MountSolution s = solveMount(truth.model(), crosshairs(truth, kDemo, 5, 5), options);
  EXPECT_FALSE(s.ok);
  EXPECT_TRUE(contains(s.error, "intrinsics and distortion together")) << s.error;
}

TEST(MountSolverDistortion, WithoutTheOptionNoDistortionIsReported)
{
  const Lens truth;
  const MountSolution s = solveMount(truth.model(), crosshairs(truth, kDemo, 5, 5));
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_TRUE(s.distortion.none());
  EXPECT_EQ(0.0, s.distortion_stddev[0]);
}
