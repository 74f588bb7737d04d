// Dense mount solver (issue 24): mount and k1, k2 from thousands of floor points made by OpenCV
// directly from a true mount and lens (distortion_oracle.h): accuracy against the truth (mount,
// k1, k2, the floor error of the fitted model over the lit area), with noise and 3 % gross
// outliers, with and without a prior; what fixing the distortion costs; every refusal.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "distortion_oracle.h"
#include "rviz_projector/core/dense_mount_solver.h"

using distortion_oracle::Lens;
using distortion_oracle::Noise;
using mount_oracle::kDeg;
using mount_oracle::Mount;
using rviz_projector::DenseMountSolution;
using rviz_projector::DenseSolveOptions;
using rviz_projector::FloorPoint;
using rviz_projector::LensDistortion;
using rviz_projector::ProjectorMount;
using rviz_projector::solveMountDense;

namespace
{
/// The demo's mount: 1.2 m up, 0.15 m ahead of base_link, pitch 0.876 rad.
const Mount kDemo{0.15, 0.0, 1.2, 0.0, 0.876, 0.0};
/// Yawed and rolled.
const Mount kTurned{0.10, -0.05, 1.0, 0.05, 0.75, 0.3};

struct Case
{
  const char* name;
  Mount mount;
  double k1, k2;
  Noise noise;
};

std::ostream& operator<<(std::ostream& os, const Case& c)
{
  return os << c.name;
}

Lens fittedLens(const DenseMountSolution& s)
{
  Lens lens;
  if (!s.distortion.none())
  {
    lens.d = s.distortion.coefficients();
    lens.d.resize(5, 0.0);
  }
  return lens;
}

ProjectorMount toMount(const Mount& m)
{
  return {m.x, m.y, m.z, m.roll, m.pitch, m.yaw};
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

void expectRefused(const DenseMountSolution& s, const std::string& part)
{
  EXPECT_FALSE(s.ok) << "expected a refusal naming '" << part << "'";
  EXPECT_TRUE(contains(s.error, part)) << "error '" << s.error << "' does not name '" << part << "'";
}

class DenseAccuracy : public ::testing::TestWithParam<Case>
{
};
}  // namespace

TEST_P(DenseAccuracy, MountDistortionAndFloorErrorMatchTheTruth)
{
  const Case& c = GetParam();
  const Lens truth = distortion_oracle::lensWith(c.k1, c.k2);
  distortion_oracle::Options o;
  o.noise = c.noise;
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, c.mount, o);
  ASSERT_GT(points.size(), 5000u);

  const auto t0 = std::chrono::steady_clock::now();
  const DenseMountSolution s = solveMountDense(truth.model(), points, nullptr);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(s.ok) << s.error;
  std::cout << "[ info ] " << c.name << ": " << points.size() << " points in " << seconds << " s; " << s.inliers
            << " inliers, " << s.outliers << " outliers, rms " << s.rms_px << " px, median " << s.median_mm
            << " mm, max " << s.max_mm << " mm; k1 " << (s.distortion.none() ? 0.0 : s.distortion.coefficients()[0])
            << " +- " << s.k_stddev[0] << ", k2 " << (s.distortion.none() ? 0.0 : s.distortion.coefficients()[1])
            << " +- " << s.k_stddev[1] << "\n";

  const Mount fitted = mount_oracle::fromSolution(s.mount);
  EXPECT_LT(distortion_oracle::positionError(fitted, c.mount), 0.002);
  EXPECT_LT(mount_oracle::rotationAngle(fitted, c.mount), 0.05 * kDeg);
  const Lens lens = fittedLens(s);
  EXPECT_NEAR(lens.d[0], c.k1, 0.01);
  EXPECT_NEAR(lens.d[1], c.k2, 0.06);
  EXPECT_EQ(0.0, lens.d[2]);
  EXPECT_EQ(0.0, lens.d[3]);
  EXPECT_EQ(0.0, lens.d[4]);
  const distortion_oracle::FloorError e = distortion_oracle::floorError(truth, c.mount, lens, fitted);
  EXPECT_GT(e.count, 500);
  EXPECT_LE(e.median_mm, 1.0);
  EXPECT_LE(e.max_mm, 3.0);
  // About 3 % outliers, all caught (each is >= 20 px off), and no more than 1 % of the good ones.
  const int planted = static_cast<int>(0.03 * points.size());
  EXPECT_GT(s.outliers, planted / 2);
  EXPECT_LT(s.outliers, planted * 3 / 2 + static_cast<int>(0.01 * points.size()));
  EXPECT_LT(s.rms_px, 1.0);
  EXPECT_LE(s.median_mm, s.max_mm);
  EXPECT_FALSE(s.expected.empty());
}

INSTANTIATE_TEST_SUITE_P(
    Lenses, DenseAccuracy,
    ::testing::Values(Case{"demo_no_distortion", kDemo, 0.0, 0.0, Noise::Uniform},
                      Case{"demo_k1_minus_0_05", kDemo, -0.05, 0.0, Noise::Uniform},
                      Case{"demo_k1_plus_0_10", kDemo, 0.10, 0.0, Noise::Gaussian},
                      Case{"demo_wide_angle", kDemo, -0.2, 0.05, Noise::Gaussian},
                      Case{"turned_wide_angle", kTurned, -0.2, 0.05, Noise::Uniform},
                      Case{"turned_k1_plus_0_10", kTurned, 0.10, 0.0, Noise::Gaussian}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(DenseMountSolver, TwentyThousandPointsFromAPriorThreeDegreesAndFiveCentimetresOff)
{
  const Lens truth = distortion_oracle::lensWith(-0.2, 0.05);
  distortion_oracle::Options o;
  o.step = 7.0;
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, o);
  ASSERT_GT(points.size(), 15000u);
  const ProjectorMount prior{kDemo.x + 0.03, kDemo.y - 0.03, kDemo.z + 0.03, 1.7 * kDeg, kDemo.pitch - 1.7 * kDeg,
                             1.7 * kDeg};
  for (bool homography : {true, false})
  {
    SCOPED_TRACE(homography ? "homography and prior starts" : "the prior start alone");
    DenseSolveOptions options;
    options.homography_start = homography;
    const auto t0 = std::chrono::steady_clock::now();
    const DenseMountSolution s = solveMountDense(truth.model(), points, &prior, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << "[ info ] " << points.size() << " points solved in " << seconds << " s ("
              << (homography ? "homography and prior" : "prior alone") << ")\n";
    ASSERT_TRUE(s.ok) << s.error;
    const Mount fitted = mount_oracle::fromSolution(s.mount);
    EXPECT_LT(distortion_oracle::positionError(fitted, kDemo), 0.002);
    EXPECT_LT(mount_oracle::rotationAngle(fitted, kDemo), 0.05 * kDeg);
    const distortion_oracle::FloorError e = distortion_oracle::floorError(truth, kDemo, fittedLens(s), fitted);
    EXPECT_LE(e.median_mm, 1.0);
    EXPECT_LE(e.max_mm, 3.0);
  }
  DenseSolveOptions no_start;
  no_start.homography_start = false;
  expectRefused(solveMountDense(truth.model(), points, nullptr, no_start), "nothing to start from");
}

TEST(DenseMountSolver, FixingTheDistortionOfAWideAngleLensCostsCentimetres)
{
  const Lens truth = distortion_oracle::lensWith(-0.2, 0.05);
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, {});
  DenseSolveOptions fixed;
  fixed.fit_distortion = false;
  fixed.outlier_px = 100.0;  // the pinhole cannot match the edges: keep them, to see the cost
  const DenseMountSolution s = solveMountDense(truth.model(), points, &static_cast<const ProjectorMount&>(toMount(kDemo)),
                                               fixed);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_TRUE(s.distortion.none());
  const distortion_oracle::FloorError e =
      distortion_oracle::floorError(truth, kDemo, Lens(), mount_oracle::fromSolution(s.mount));
  std::cout << "[ info ] k1, k2 fixed at 0: floor error median " << e.median_mm << " mm, max " << e.max_mm << " mm\n";
  EXPECT_GT(e.max_mm, 20.0);

  // The prior's distortion, when given and kept, is used as it is: exact.
  DenseSolveOptions known;
  known.fit_distortion = false;
  known.distortion = LensDistortion(LensDistortion::Model::PlumbBob, truth.d);
  const DenseMountSolution k = solveMountDense(truth.model(), points, nullptr, known);
  ASSERT_TRUE(k.ok) << k.error;
  EXPECT_EQ(truth.d, k.distortion.coefficients());
  const distortion_oracle::FloorError ek =
      distortion_oracle::floorError(truth, kDemo, truth, mount_oracle::fromSolution(k.mount));
  EXPECT_LE(ek.max_mm, 3.0);
}

TEST(DenseMountSolver, RefusesTooFewPoints)
{
  const Lens truth;
  distortion_oracle::Options o;
  o.step = 120.0;
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, o);
  ASSERT_LT(points.size(), 100u);
  ASSERT_GE(points.size(), 20u);
  expectRefused(solveMountDense(truth.model(), points, nullptr), "need at least 100 points");
  expectRefused(solveMountDense(truth.model(), {}, nullptr), "got 0");
}

TEST(DenseMountSolver, RefusesPointsCoveringTooLittleOfTheImage)
{
  const Lens truth;
  distortion_oracle::Options o;
  o.step = 4.0;
  o.u0 = 400, o.u1 = 800, o.v0 = 400, o.v1 = 700;  // 3 x 3 .. 4 x 4 of the 10 x 10 cells
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, o);
  ASSERT_GT(points.size(), 1000u);
  expectRefused(solveMountDense(truth.model(), points, nullptr), "at least 25% is needed");
}

TEST(DenseMountSolver, RefusesFittingTheDistortionFromPointsNearTheCentreOnly)
{
  const Lens truth = distortion_oracle::lensWith(-0.05, 0.0);
  distortion_oracle::Options o;
  o.u0 = 240, o.u1 = 1040, o.v0 = 380, o.v1 = 800;  // around the principal point (640, 750)
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, o);
  expectRefused(solveMountDense(truth.model(), points, nullptr), "of the image corner's radius");
  // Without the distortion fit the same points are accepted.
  DenseSolveOptions fixed;
  fixed.fit_distortion = false;
  fixed.outlier_px = 3.0;
  EXPECT_TRUE(solveMountDense(truth.model(), points, nullptr, fixed).ok);
}

TEST(DenseMountSolver, RefusesADistortionThatFoldsInsideTheImage)
{
  // k1 = -1.5: r (1 - 1.5 r^2) turns back at r = 0.47 (distorted 0.31), the corner is at 0.52.
  // Points where the lens is still monotonic (the oracle drops the rest).
  const Lens truth = distortion_oracle::lensWith(-1.5, 0.0);
  distortion_oracle::Options o;
  o.noise = Noise::None;
  o.outliers = 0.0;
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, o);
  ASSERT_GT(points.size(), 1000u);
  DenseSolveOptions options;
  options.min_radius_fraction = 0.0;
  expectRefused(solveMountDense(truth.model(), points, &static_cast<const ProjectorMount&>(toMount(kDemo)), options),
                "folds back");
}

TEST(DenseMountSolver, RefusesAWeakSolve)
{
  // 150 points with 3 px noise: pose and distortion too uncertain for the limits.
  const Lens truth = distortion_oracle::lensWith(-0.05, 0.0);
  distortion_oracle::Options o;
  o.step = 80.0;
  o.noise = Noise::Gaussian;
  o.gaussian_sigma = 3.0;
  o.outliers = 0.0;
  const std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, o);
  ASSERT_GE(points.size(), 100u);
  DenseSolveOptions options;
  options.outlier_px = 20.0;
  options.min_coverage = 0.1;
  expectRefused(solveMountDense(truth.model(), points, nullptr, options), "the solve is weak");
}

TEST(DenseMountSolver, RefusesAProjectorBelowTheFloor)
{
  // A projector 1.2 m below the plane looking up at it: physically impossible for a floor.
  const Mount below{0.15, 0.0, -1.2, 0.0, -0.876, 0.0};
  const Lens truth;
  std::vector<FloorPoint> points;
  distortion_oracle::Options o;
  o.outliers = 0.0;
  for (int v = 4; v < truth.height; v += 8)
  {
    for (int u = 4; u < truth.width; u += 8)
    {
      // The ray through the pixel, hand-computed, up to z = 0.
      const mount_oracle::Mat r = mount_oracle::parentROptical(below);
      const double ray[3] = {(u - truth.cx) / truth.fx, (v - truth.cy) / truth.fy, 1.0};
      double d[3] = {0, 0, 0};
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k)
          d[i] += r[i][k] * ray[k];
      if (!(d[2] > 1e-3))
        continue;
      const double s = 1.2 / d[2];
      if (s * std::hypot(d[0], d[1]) > 8.0)
        continue;
      points.push_back({static_cast<int>(points.size()), {static_cast<double>(u), static_cast<double>(v)},
                        {below.x + s * d[0], below.y + s * d[1], 0.0}});
    }
  }
  ASSERT_GT(points.size(), 1000u);
  const ProjectorMount prior = toMount(below);
  const DenseMountSolution s = solveMountDense(truth.model(), points, &prior);
  expectRefused(s, "at or below the points' plane");
  // Without a prior no start puts the projector above the floor.
  expectRefused(solveMountDense(truth.model(), points, nullptr), "no start pose");
}

TEST(DenseMountSolver, RefusesBadInput)
{
  const Lens truth;
  std::vector<FloorPoint> points = distortion_oracle::correspondences(truth, kDemo, {});
  std::vector<FloorPoint> nan = points;
  nan[10].world.x = std::nan("");
  expectRefused(solveMountDense(truth.model(), nan, nullptr), "not a finite number");
  std::vector<FloorPoint> off_plane = points;
  off_plane[10].world.z = 0.3;
  expectRefused(solveMountDense(truth.model(), off_plane, nullptr), "one plane z = const");
  DenseSolveOptions bad;
  bad.outlier_px = std::nan("");
  expectRefused(solveMountDense(truth.model(), points, nullptr, bad), "finite");
  ProjectorMount prior = toMount(kDemo);
  prior.pitch = INFINITY;
  expectRefused(solveMountDense(truth.model(), points, &prior), "prior mount is not finite");
  expectRefused(solveMountDense(rviz_projector::PinholeModel(), points, nullptr), "no image size");
}
