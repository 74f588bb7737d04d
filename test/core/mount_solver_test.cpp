// Mount solver (issue 12): pixelOnPlane by hand, residuals, warnings, the expected error, other
// planes and off-plane points, many points with several outliers, and every bad input refused with
// a message naming the problem. Synthetic data from the test's own oracle (mount_test_oracle.h).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mount_test_oracle.h"
#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/projector_mount.h"

using mount_oracle::kDeg;
using mount_oracle::Lens;
using mount_oracle::Mount;
using rviz_projector::FloorPoint;
using rviz_projector::MountSolution;
using rviz_projector::MountSolverOptions;
using rviz_projector::opticalPoseOfMount;
using rviz_projector::PinholeModel;
using rviz_projector::pixelOnPlane;
using rviz_projector::solveMount;
using rviz_projector::Vec2;
using rviz_projector::Vec3;

namespace
{
const Lens kLens = mount_oracle::pa503w();
const Mount kMount{0.15, 0.0, 1.2, 0.0, 50 * kDeg, 0.0};

std::vector<FloorPoint> pattern(const Lens& lens, const Mount& m, int rows = 3, int cols = 3, double max_d = 10.0)
{
  std::vector<Vec2> px;
  for (const rviz_projector::Crosshair& c : rviz_projector::crosshairPattern(lens.width, lens.height, rows, cols))
    px.push_back(c.pixel);
  std::vector<FloorPoint> pts;
  EXPECT_TRUE(mount_oracle::floorPoints(lens, m, px, pts, max_d));
  return pts;
}

bool contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

bool anyContains(const std::vector<std::string>& texts, const std::string& part)
{
  for (const std::string& t : texts)
    if (contains(t, part))
      return true;
  return false;
}

void expectRefused(const PinholeModel& lens, const std::vector<FloorPoint>& pts, const std::string& part,
                   const MountSolverOptions& options = MountSolverOptions())
{
  const MountSolution s = solveMount(lens, pts, options);
  EXPECT_FALSE(s.ok) << "expected a refusal naming '" << part << "'";
  EXPECT_TRUE(contains(s.error, part)) << "error '" << s.error << "' does not name '" << part << "'";
}
}  // namespace

TEST(PixelOnPlane, HandComputedStraightDown)
{
  // Beam straight down from 1 m: optical x = parent -y, optical y = parent -x (pitch 90 degrees).
  const PinholeModel lens(100, 100, 100.0, 100.0, 50.0, 50.0);
  const rviz_projector::RigidTransform t = opticalPoseOfMount({0.0, 0.0, 1.0, 0.0, M_PI / 2, 0.0});
  Vec3 out;
  ASSERT_TRUE(pixelOnPlane(lens, t, {60.0, 50.0}, 0.0, out));  // ray (0.1, 0, 1)
  EXPECT_NEAR(out.x, 0.0, 1e-12);
  EXPECT_NEAR(out.y, -0.1, 1e-12);
  EXPECT_NEAR(out.z, 0.0, 1e-12);
  ASSERT_TRUE(pixelOnPlane(lens, t, {50.0, 70.0}, 0.0, out));  // ray (0, 0.2, 1)
  EXPECT_NEAR(out.x, -0.2, 1e-12);
  EXPECT_NEAR(out.y, 0.0, 1e-12);
  ASSERT_TRUE(pixelOnPlane(lens, t, {60.0, 50.0}, 0.5, out));  // half way down: half the offset
  EXPECT_NEAR(out.y, -0.05, 1e-12);
  EXPECT_NEAR(out.z, 0.5, 1e-12);
  EXPECT_FALSE(pixelOnPlane(lens, t, {60.0, 50.0}, 2.0, out)) << "plane above the projector: behind the lens";
  const rviz_projector::RigidTransform level = opticalPoseOfMount({0.0, 0.0, 1.0, 0.0, 0.0, 0.0});
  EXPECT_FALSE(pixelOnPlane(lens, level, {50.0, 50.0}, 0.0, out)) << "horizontal ray never meets the floor";
  EXPECT_FALSE(pixelOnPlane(lens, level, {50.0, 40.0}, 0.0, out)) << "ray above the horizon";
  EXPECT_TRUE(pixelOnPlane(lens, level, {50.0, 60.0}, 0.0, out));
  EXPECT_NEAR(out.x, 10.0, 1e-9);  // 1 m down at a slope of 0.1
}

TEST(MountSolver, ResidualsInPixelsAndMillimetres)
{
  std::vector<FloorPoint> pts = pattern(kLens, kMount);
  pts[4].world.x += 0.010;  // the centre crosshair measured 1 cm too far
  const MountSolution s = solveMount(kLens.model(), pts);
  ASSERT_TRUE(s.ok) << s.error;
  ASSERT_EQ(s.residuals.size(), pts.size());
  EXPECT_EQ(s.residuals[4].id, pts[4].id);
  // The fit absorbs part of the error: the moved point keeps most of it, the others little.
  EXPECT_GT(s.residuals[4].mm, 5.0);
  EXPECT_LT(s.residuals[4].mm, 10.5);
  double sum_px = 0.0, sum_mm = 0.0;
  for (const rviz_projector::PointResidual& r : s.residuals)
  {
    EXPECT_FALSE(r.outlier);
    sum_px += r.px * r.px, sum_mm += r.mm * r.mm;
    // Both measure the same miss: at 1.5-4.5 m and f = 1900 px a millimetre is 0.4-1.3 px.
    if (r.mm > 0.5)
    {
      EXPECT_GT(r.px / r.mm, 0.2) << r.id;
      EXPECT_LT(r.px / r.mm, 2.0) << r.id;
    }
  }
  EXPECT_NEAR(s.rms_px, std::sqrt(sum_px / 9), 1e-9);
  EXPECT_NEAR(s.rms_mm, std::sqrt(sum_mm / 9), 1e-9);
}

TEST(MountSolver, AnyPlaneAndOffPlanePointsWithAFixedLens)
{
  // All points on a platform 0.4 m high (IPPE on a plane other than z = 0).
  std::vector<FloorPoint> raised;
  int id = 1;
  for (const rviz_projector::Crosshair& c : rviz_projector::crosshairPattern(kLens.width, kLens.height, 3, 3))
  {
    Vec3 w;
    ASSERT_TRUE(mount_oracle::hit(kLens, kMount, c.pixel, 0.4, w));
    raised.push_back({id++, c.pixel, w});
  }
  MountSolution s = solveMount(kLens.model(), raised);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_NEAR(s.mount.z, kMount.z, 1e-6);
  EXPECT_NEAR(s.mount.pitch, kMount.pitch, 1e-7);
  // Floor points and three box tops (SQPnP start, not coplanar).
  std::vector<FloorPoint> mixed = pattern(kLens, kMount);
  for (int i = 0; i < 3; ++i)
  {
    const Vec2 px{300.0 + 300 * i, 250.0 + 150 * i};
    Vec3 w;
    ASSERT_TRUE(mount_oracle::hit(kLens, kMount, px, 0.3 + 0.1 * i, w));
    mixed.push_back({20 + i, px, w});
  }
  s = solveMount(kLens.model(), mixed);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_NEAR(s.mount.x, kMount.x, 1e-6);
  EXPECT_NEAR(s.mount.z, kMount.z, 1e-6);
  EXPECT_NEAR(s.mount.pitch, kMount.pitch, 1e-7);
  EXPECT_NEAR(s.mount.yaw, kMount.yaw, 1e-7);
}

TEST(MountSolver, HundredPointsWithThreeOutliers)
{
  const Mount m{0.1, 0.0, 1.5, 0.0, 60 * kDeg, 0.0};
  std::vector<FloorPoint> pts = pattern(kLens, m, 10, 10, 20.0);
  ASSERT_EQ(pts.size(), 100u);
  pts[0].world.y += 0.12;
  pts[55].world.x -= 0.08;
  pts[99].world.x += 0.20;
  const MountSolution s = solveMount(kLens.model(), pts);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_EQ(s.outliers, (std::vector<int>{1, 56, 100}));
  EXPECT_NEAR(s.mount.z, m.z, 1e-6);
  EXPECT_NEAR(s.mount.pitch, m.pitch, 1e-7);
  EXPECT_TRUE(s.residuals[99].outlier);
  EXPECT_NEAR(s.residuals[99].mm, 200.0, 0.1);
}

// Issue 23, defect 4: a point whose z is wrong (typed in cm: 1.6 instead of 0.016, or a plane its
// crosshair's ray cannot reach from a projector 1.5 m up) is an outlier like a wrong x or y.
TEST(MountSolver, APointWhoseZTheRayCannotReachIsFlaggedNotFatal)
{
  const Mount m{0.1, 0.0, 1.5, 0.0, 60 * kDeg, 0.0};
  for (std::size_t bad = 0; bad < 9; ++bad)
  {
    std::vector<FloorPoint> pts = pattern(kLens, m);
    ASSERT_EQ(pts.size(), 9u);
    pts[bad].world.z = 1.6;  // above the projector: no downward ray reaches it
    const MountSolution s = solveMount(kLens.model(), pts);
    ASSERT_TRUE(s.ok) << "point " << pts[bad].id << " at z = 1.6: " << s.error;
    EXPECT_EQ(s.outliers, (std::vector<int>{pts[bad].id})) << "bad point " << pts[bad].id;
    EXPECT_NEAR(s.mount.z, m.z, 1e-6);
    EXPECT_NEAR(s.mount.pitch, m.pitch, 1e-7);
    EXPECT_NEAR(s.mount.x, m.x, 1e-6);
    EXPECT_TRUE(s.residuals[bad].outlier);
    EXPECT_FALSE(std::isfinite(s.residuals[bad].mm)) << "a ray that cannot reach z = 1.6 has no floor residual";
    EXPECT_LT(s.rms_mm, 1e-3);
  }
}

TEST(MountSolver, APointTypedInCentimetresInZIsFlagged)
{
  const Mount m{0.1, 0.0, 1.5, 0.0, 60 * kDeg, 0.0};
  std::vector<FloorPoint> pts = pattern(kLens, m);
  pts[4].world.z = 0.8;  // reachable, but far off where its ray meets that plane
  const MountSolution s = solveMount(kLens.model(), pts);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_EQ(s.outliers, (std::vector<int>{pts[4].id}));
  EXPECT_NEAR(s.mount.z, m.z, 1e-6);
}

TEST(MountSolver, ExpectedErrorAtTheCornersAndTwoMetresAheadFollowsTheTapeError)
{
  const std::vector<FloorPoint> pts = pattern(kLens, kMount);
  MountSolverOptions careful;
  careful.tape_error = 0.001;
  const MountSolution coarse = solveMount(kLens.model(), pts);
  const MountSolution fine = solveMount(kLens.model(), pts, careful);
  ASSERT_TRUE(coarse.ok && fine.ok);
  ASSERT_EQ(coarse.expected.size(), 5u);
  const char* where[5] = {"crosshair 1 (top left)", "crosshair 3 (top right)", "crosshair 7 (bottom left)",
                          "crosshair 9 (bottom right)", "2 m ahead"};
  for (std::size_t i = 0; i < 5; ++i)
  {
    EXPECT_EQ(coarse.expected[i].where, where[i]);
    // Exact data: the error comes from the tape error alone, millimetres, proportional to it.
    EXPECT_GT(coarse.expected[i].mm, 1.0) << where[i];
    EXPECT_LT(coarse.expected[i].mm, 15.0) << where[i];
    EXPECT_NEAR(coarse.expected[i].mm / fine.expected[i].mm, 3.0, 1e-6) << where[i];
  }
  EXPECT_NEAR(coarse.expected[0].world.x, pts[0].world.x, 1e-6);
  EXPECT_NEAR(coarse.expected[4].world.x, kMount.x + 2.0, 1e-9);
  EXPECT_NEAR(coarse.expected[4].world.y, 0.0, 1e-9);
  for (int i = 0; i < 6; ++i)
    EXPECT_GT(coarse.covariance[static_cast<std::size_t>(7 * i)], 0.0);
  // A steep mount does not reach 2 m ahead: said, not reported.
  const Mount steep{0.0, 0.0, 0.6, 0.0, 80 * kDeg, 0.0};
  const MountSolution s = solveMount(kLens.model(), pattern(kLens, steep));
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_EQ(s.expected.size(), 4u);
  EXPECT_TRUE(anyContains(s.warnings, "2 m ahead")) << "no warning about 2 m ahead";
}

TEST(MountSolver, WeakGeometryWarns)
{
  std::vector<FloorPoint> five = pattern(kLens, kMount);
  five.resize(5);
  MountSolution s = solveMount(kLens.model(), five);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_TRUE(anyContains(s.warnings, "only 5 points"));
  EXPECT_FALSE(anyContains(pattern(kLens, kMount).empty() ? std::vector<std::string>{}
                                                           : solveMount(kLens.model(), pattern(kLens, kMount)).warnings,
                           "only"));
  // Two rows 40 px apart across the image: nearly collinear.
  std::vector<Vec2> px;
  for (int i = 0; i < 5; ++i)
  {
    px.push_back({150.0 + 240 * i, 380.0});
    px.push_back({150.0 + 240 * i, 420.0});
  }
  std::vector<FloorPoint> narrow;
  ASSERT_TRUE(mount_oracle::floorPoints(kLens, kMount, px, narrow));
  s = solveMount(kLens.model(), narrow);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_TRUE(anyContains(s.warnings, "nearly collinear"));
  // A 3x3 grid within the middle 30% of the image.
  px.clear();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      px.push_back({448.0 + 192 * c, 280.0 + 120 * r});
  std::vector<FloorPoint> centre;
  ASSERT_TRUE(mount_oracle::floorPoints(kLens, kMount, px, centre));
  s = solveMount(kLens.model(), centre);
  ASSERT_TRUE(s.ok) << s.error;
  EXPECT_TRUE(anyContains(s.warnings, "close to the image centre"));
}

TEST(MountSolver, BadInputIsRefusedWithTheReason)
{
  const PinholeModel lens = kLens.model();
  const std::vector<FloorPoint> good = pattern(kLens, kMount);
  ASSERT_TRUE(solveMount(lens, good).ok);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();

  expectRefused(lens, {}, "at least 4 points");
  expectRefused(lens, std::vector<FloorPoint>(good.begin(), good.begin() + 3), "at least 4 points");
  auto with = [&](auto change) {
    std::vector<FloorPoint> p = good;
    change(p);
    return p;
  };
  expectRefused(lens, with([&](auto& p) { p[2].world.x = nan; }), "not a finite number");
  expectRefused(lens, with([&](auto& p) { p[2].world.z = inf; }), "not a finite number");
  expectRefused(lens, with([&](auto& p) { p[5].pixel.y = nan; }), "not a finite number");
  expectRefused(lens, with([&](auto& p) { p[3].id = p[1].id; }), "appears more than once");
  expectRefused(lens, with([&](auto& p) { p[8].pixel.x = 1280.0; }), "outside the projector's image");
  expectRefused(lens, with([&](auto& p) { p[0].pixel.y = -0.6; }), "outside the projector's image");
  expectRefused(lens, with([&](auto& p) { p[4].world.x = 2013.0; }), "look like millimetres");
  expectRefused(lens, with([&](auto& p) { p[4].world.y = -871.0; }), "look like millimetres");
  expectRefused(lens, with([&](auto& p) { p[4].world.z = 60.0; }), "look like millimetres");
  // One row of crosshairs: collinear pixels and floor points.
  expectRefused(lens, pattern(kLens, kMount, 1, 6), "collinear");
  // A lens with a stereo baseline, or none at all.
  expectRefused(PinholeModel(1280, 800, 1900, 1900, 640, 817, 0.1, 0.0), good, "Tx");
  expectRefused(PinholeModel(), good, "no image size");
  // The floor points mirrored (y sign flipped): exactly what a projector below the floor, turned
  // 180 degrees about x, would see; no pose has the projector above them.
  expectRefused(lens, with([&](auto& p) { for (FloorPoint& q : p) q.world.y = -q.world.y; }), "above the points");
  // A point behind the projector (x sign wrong) is an outlier like any other wrong x (issue 23):
  // solved without it, and named.
  {
    const MountSolution behind = solveMount(lens, with([&](auto& p) { p[4].world.x = -p[4].world.x - 1.0; }));
    EXPECT_TRUE(behind.ok) << behind.error;
    EXPECT_EQ(behind.outliers, (std::vector<int>{good[4].id}));
  }
  // Points that agree with no mount: ids mixed up (the pattern measured upside down).
  expectRefused(lens, with([&](auto& p) { std::swap(p[0].world, p[8].world); std::swap(p[2].world, p[6].world);
                                          std::swap(p[1].world, p[7].world); }),
                "do not agree with one mount");
  MountSolverOptions bad_options;
  bad_options.outlier_distance = 0.0;
  expectRefused(lens, good, "outlier_distance", bad_options);
  // Intrinsics from floor points only.
  MountSolverOptions intrinsics;
  intrinsics.fit_intrinsics = true;
  expectRefused(lens, good, "floor points alone cannot tell focal length", intrinsics);
}

TEST(MountSolver, FewPointsThatDisagreeAreRefused)
{
  std::vector<FloorPoint> four = pattern(kLens, kMount, 2, 2);
  four[1].world.x += 0.3;
  const MountSolution s = solveMount(kLens.model(), four);
  EXPECT_FALSE(s.ok);
  EXPECT_TRUE(contains(s.error, "do not agree") || contains(s.error, "in front of")) << s.error;
}

// The CLI's --tape-error sets the outlier threshold: 10 tape errors, never under 3 cm (by hand).
TEST(MountSolverOptions, OutlierThresholdFollowsTheTapeError)
{
  EXPECT_DOUBLE_EQ(0.03, rviz_projector::MountSolverOptions::forTapeError(0.003).outlier_distance);
  EXPECT_DOUBLE_EQ(0.03, rviz_projector::MountSolverOptions::forTapeError(0.001).outlier_distance);
  EXPECT_DOUBLE_EQ(0.1, rviz_projector::MountSolverOptions::forTapeError(0.01).outlier_distance);
  EXPECT_DOUBLE_EQ(0.01, rviz_projector::MountSolverOptions::forTapeError(0.01).tape_error);
}
