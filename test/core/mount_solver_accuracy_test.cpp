// Mount solver accuracy (issue 12) on synthetic data made here from known mounts, projected by the
// test's own oracle (mount_test_oracle.h): exact points, 3 mm tape noise, an outlier, intrinsics.
//
// How mounts are drawn: a fixed grid of heights 0.3-1.5 m, pitch 20-80 degrees and roll/yaw up to
// +-10 degrees, for three lenses (the PA503W with its principal point below the image, a centred
// lens, a Full HD one); a mount is used only when all 9 crosshairs of the 3x3 pattern hit the floor
// in front of the projector within 10 m of it (a shallow mount throws the top row over the horizon).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
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
std::vector<Vec2> patternPixels(const Lens& lens, int rows = 3, int cols = 3)
{
  std::vector<Vec2> out;
  for (const rviz_projector::Crosshair& c : rviz_projector::crosshairPattern(lens.width, lens.height, rows, cols))
  {
    out.push_back(c.pixel);
  }
  return out;
}

struct Case
{
  Lens lens;
  Mount mount;
  std::string name;
};

std::string describe(const Lens& lens, const Mount& m)
{
  char buf[200];
  std::snprintf(buf, sizeof buf, "lens f=%.0f cy=%.0f, mount z=%.2f roll=%.1f pitch=%.1f yaw=%.1f deg", lens.fx,
                lens.cy, m.z, m.roll / kDeg, m.pitch / kDeg, m.yaw / kDeg);
  return buf;
}

std::vector<Case> gridCases()
{
  std::vector<Case> cases;
  for (const Lens& lens : {mount_oracle::pa503w(), mount_oracle::centred(), mount_oracle::fullHd()})
    for (double z : {0.3, 0.8, 1.5})
      for (double pitch : {20.0, 35.0, 50.0, 65.0, 80.0})
        for (const auto& [roll, yaw] : std::vector<std::pair<double, double>>{{0, 0}, {10, -10}, {-10, 10}, {5, 10}})
        {
          const Mount m{0.15, -0.05, z, roll * kDeg, pitch * kDeg, yaw * kDeg};
          std::vector<FloorPoint> pts;
          if (mount_oracle::floorPoints(lens, m, patternPixels(lens), pts))
          {
            cases.push_back({lens, m, describe(lens, m)});
          }
        }
  return cases;
}

double percentile(std::vector<double> v, double q)
{
  std::sort(v.begin(), v.end());
  return v.empty() ? NAN : v[static_cast<std::size_t>(std::min<double>(v.size() - 1, std::floor(q * v.size())))];
}

/// Floor error (m) at a 20 x 20 grid of projector pixels between the true and the solved mount,
/// where the true ray lands within 10 m.
void gridErrors(const Lens& lens, const Mount& truth, const Mount& solved, std::vector<double>& out)
{
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j)
    {
      const Vec2 px{(i + 0.5) * lens.width / 20.0 - 0.5, (j + 0.5) * lens.height / 20.0 - 0.5};
      Vec3 a, b;
      if (!mount_oracle::hit(lens, truth, px, 0.0, a) || std::hypot(a.x - truth.x, a.y - truth.y) > 10.0)
        continue;
      if (!mount_oracle::hit(lens, solved, px, 0.0, b))
      {
        out.push_back(HUGE_VAL);
        continue;
      }
      out.push_back(std::hypot(a.x - b.x, a.y - b.y));
    }
}
}  // namespace

TEST(MountSolverAccuracy, ExactPointsRecoverThePose)
{
  const std::vector<Case> cases = gridCases();
  std::printf("exact: %zu of 180 grid mounts have the whole pattern on the floor within 10 m\n", cases.size());
  ASSERT_GE(cases.size(), 80u);
  for (const Case& c : cases)
  {
    std::vector<FloorPoint> pts;
    ASSERT_TRUE(mount_oracle::floorPoints(c.lens, c.mount, patternPixels(c.lens), pts));
    const MountSolution s = solveMount(c.lens.model(), pts);
    ASSERT_TRUE(s.ok) << c.name << ": " << s.error;
    const Mount got = mount_oracle::fromSolution(s.mount);
    EXPECT_LE(std::hypot(got.x - c.mount.x, got.y - c.mount.y, got.z - c.mount.z), 1e-4) << c.name;
    EXPECT_LE(mount_oracle::rotationAngle(got, c.mount), 0.01 * kDeg) << c.name;
    EXPECT_NEAR(got.pitch, c.mount.pitch, 0.01 * kDeg) << c.name;
    EXPECT_NEAR(got.roll, c.mount.roll, 0.01 * kDeg) << c.name;
    EXPECT_NEAR(got.yaw, c.mount.yaw, 0.01 * kDeg) << c.name;
    EXPECT_TRUE(s.outliers.empty()) << c.name;
    EXPECT_LT(s.rms_px, 1e-6) << c.name;
    EXPECT_LT(s.rms_mm, 1e-4) << c.name;
  }
}

/// Mounts of the noise tests: typical and extreme ones of the grid's range.
std::vector<Case> noiseCases()
{
  std::vector<Case> cases;
  const std::vector<std::pair<Lens, Mount>> raw = {
      {mount_oracle::pa503w(), {0.15, 0.0, 1.2, 0.0, 50 * kDeg, 0.0}},
      {mount_oracle::pa503w(), {0.10, 0.05, 0.3, -5 * kDeg, 65 * kDeg, 10 * kDeg}},
      {mount_oracle::pa503w(), {0.15, 0.0, 1.5, 10 * kDeg, 35 * kDeg, -10 * kDeg}},
      {mount_oracle::centred(), {0.0, 0.0, 0.8, 0.0, 50 * kDeg, 5 * kDeg}},
      {mount_oracle::centred(), {0.2, -0.1, 1.5, -10 * kDeg, 80 * kDeg, 10 * kDeg}},
      {mount_oracle::fullHd(), {0.15, 0.0, 1.0, 3 * kDeg, 45 * kDeg, -3 * kDeg}},
  };
  for (const auto& [lens, m] : raw)
    cases.push_back({lens, m, describe(lens, m)});
  return cases;
}

TEST(MountSolverAccuracy, TapeNoiseGivesMillimetreFloorErrorAndAnHonestPrediction)
{
  for (std::size_t k = 0; k < noiseCases().size(); ++k)
  {
    const Case c = noiseCases()[k];
    std::vector<FloorPoint> exact;
    ASSERT_TRUE(mount_oracle::floorPoints(c.lens, c.mount, patternPixels(c.lens), exact)) << c.name;
    std::mt19937 rng(1000 + static_cast<unsigned>(k));
    std::normal_distribution<double> noise(0.0, 0.003);
    std::vector<double> grid;
    std::map<int, std::vector<double>> corner_measured, corner_expected;  // by crosshair id
    for (int trial = 0; trial < 100; ++trial)
    {
      std::vector<FloorPoint> pts = exact;
      for (FloorPoint& p : pts)
      {
        p.world.x += noise(rng);
        p.world.y += noise(rng);
      }
      const MountSolution s = solveMount(c.lens.model(), pts);
      ASSERT_TRUE(s.ok) << c.name << ": " << s.error;
      EXPECT_TRUE(s.outliers.empty()) << c.name;
      const Mount got = mount_oracle::fromSolution(s.mount);
      gridErrors(c.lens, c.mount, got, grid);
      // Measured vs predicted at the corner crosshairs the solver reports.
      for (const rviz_projector::ExpectedError& e : s.expected)
      {
        if (e.where.rfind("crosshair", 0) != 0)
          continue;
        const int id = std::stoi(e.where.substr(10));
        const Vec2 px = exact[static_cast<std::size_t>(id - 1)].pixel;
        Vec3 a, b;
        ASSERT_TRUE(mount_oracle::hit(c.lens, c.mount, px, 0.0, a) && mount_oracle::hit(c.lens, got, px, 0.0, b));
        corner_measured[id].push_back(1000.0 * std::hypot(a.x - b.x, a.y - b.y));
        corner_expected[id].push_back(e.mm);
      }
    }
    const double median = percentile(grid, 0.5), p95 = percentile(grid, 0.95);
    std::printf("noise 3 mm, %s: floor error median %.2f mm, p95 %.2f mm\n", c.name.c_str(), 1000 * median,
                1000 * p95);
    EXPECT_LE(median, 0.005) << c.name;
    EXPECT_LE(p95, 0.010) << c.name;
    // The expected error is a 1-sigma radial error, sqrt(trace of the floor covariance): the RMS of
    // the radial error over the trials is what it predicts (a median radial error is 0.67-0.83 of
    // it, depending on the error ellipse), so the RMS is compared with the median prediction.
    ASSERT_EQ(corner_measured.size(), 4u) << c.name << ": four corner crosshairs";
    for (const auto& [id, measured] : corner_measured)
    {
      ASSERT_EQ(measured.size(), 100u) << c.name << " crosshair " << id;
      double sum_sq = 0.0;
      for (double m : measured)
        sum_sq += m * m;
      const double rms = std::sqrt(sum_sq / measured.size());
      const double expected = percentile(corner_expected[id], 0.5);
      std::printf("  crosshair %d: measured radial error median %.2f mm, RMS %.2f mm; expected (median) %.2f mm\n",
                  id, percentile(measured, 0.5), rms, expected);
      EXPECT_LE(expected, 2.0 * rms) << c.name << " crosshair " << id;
      EXPECT_GE(expected, 0.5 * rms) << c.name << " crosshair " << id;
      EXPECT_LE(expected, 2.0 * percentile(measured, 0.5)) << c.name << " crosshair " << id;
      EXPECT_GE(expected, 0.5 * percentile(measured, 0.5)) << c.name << " crosshair " << id;
    }
  }
}

TEST(MountSolverAccuracy, APointMovedBy10cmIsFlaggedAndTheRestStaysAccurate)
{
  const std::vector<Case> cases = {noiseCases()[0], noiseCases()[3], noiseCases()[5]};
  for (std::size_t k = 0; k < cases.size(); ++k)
  {
    const Case& c = cases[k];
    std::vector<FloorPoint> exact;
    ASSERT_TRUE(mount_oracle::floorPoints(c.lens, c.mount, patternPixels(c.lens), exact)) << c.name;
    std::mt19937 rng(2000 + static_cast<unsigned>(k));
    std::normal_distribution<double> noise(0.0, 0.003);
    std::uniform_real_distribution<double> direction(-M_PI, M_PI);
    std::vector<double> grid;
    for (int trial = 0; trial < 45; ++trial)
    {
      std::vector<FloorPoint> pts = exact;
      for (FloorPoint& p : pts)
      {
        p.world.x += noise(rng);
        p.world.y += noise(rng);
      }
      const std::size_t moved = static_cast<std::size_t>(trial % 9);  // every crosshair in turn
      const double a = direction(rng);
      pts[moved].world.x += 0.1 * std::cos(a);
      pts[moved].world.y += 0.1 * std::sin(a);
      const MountSolution s = solveMount(c.lens.model(), pts);
      ASSERT_TRUE(s.ok) << c.name << ": " << s.error;
      ASSERT_EQ(s.outliers, std::vector<int>{pts[moved].id}) << c.name << ", moved crosshair " << pts[moved].id;
      EXPECT_TRUE(s.residuals[moved].outlier);
      EXPECT_GT(s.residuals[moved].mm, 60.0);
      EXPECT_LT(s.rms_mm, 10.0);
      gridErrors(c.lens, c.mount, mount_oracle::fromSolution(s.mount), grid);
    }
    const double median = percentile(grid, 0.5), p95 = percentile(grid, 0.95);
    std::printf("one point moved 10 cm, %s: floor error median %.2f mm, p95 %.2f mm\n", c.name.c_str(),
                1000 * median, 1000 * p95);
    EXPECT_LE(median, 0.005) << c.name;
    EXPECT_LE(p95, 0.010) << c.name;
  }
}
