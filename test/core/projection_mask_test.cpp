// The projection mask's geometry: scan returns on the floor, occluder columns, and the oblique near
// plane of Max lit height, against hand-computed values.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "rviz_projector/core/projection_mask.h"

using namespace rviz_projector;

namespace
{
constexpr double kPi = 3.14159265358979323846;
const float kNaNf = std::numeric_limits<float>::quiet_NaN();
const float kInff = std::numeric_limits<float>::infinity();

ScanView view(const std::vector<float>& ranges, double angle_min, double increment)
{
  ScanView s;
  s.angle_min = angle_min;
  s.angle_increment = increment;
  s.range_min = 0.1;
  s.range_max = 10.0;
  s.ranges = ranges.data();
  s.count = ranges.size();
  return s;
}
}  // namespace

TEST(ProjectionMask, ReturnsLandOnTheFloorInTheFixedFrame)
{
  // Scanner at (1, 2, 0.3) turned +90 degrees: its x axis is the fixed frame's +y.
  const RigidTransform pose = RigidTransform::fromQuaternion(0, 0, std::sin(kPi / 4), std::cos(kPi / 4), Vec3{1, 2, 0.3});
  const std::vector<float> ranges{2.0f, 1.0f, 3.0f};  // at -90, 0, +90 degrees
  std::vector<Vec2> points;
  const MaskInputCount n = scanToFloorPoints(view(ranges, -kPi / 2, kPi / 2), pose, points);
  EXPECT_EQ(n.used, 3u);
  EXPECT_EQ(n.ignored, 0u);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_NEAR(points[0].x, 3.0, 1e-9);  // -90 in the scanner = +x in the fixed frame, 2 m
  EXPECT_NEAR(points[0].y, 2.0, 1e-9);
  EXPECT_NEAR(points[1].x, 1.0, 1e-9);  // straight ahead = +y, 1 m
  EXPECT_NEAR(points[1].y, 3.0, 1e-9);
  EXPECT_NEAR(points[2].x, -2.0, 1e-9);  // +90 = -x, 3 m
  EXPECT_NEAR(points[2].y, 2.0, 1e-9);
}

TEST(ProjectionMask, InvalidReturnsAreIgnoredAndCounted)
{
  const std::vector<float> ranges{kNaNf, kInff, -kInff, 0.05f, 10.5f, 10.0f, 0.1f, 4.0f};
  std::vector<Vec2> points{Vec2{9, 9}};  // cleared first
  const MaskInputCount n = scanToFloorPoints(view(ranges, 0.0, 0.01), RigidTransform(), points);
  EXPECT_EQ(n.used, 3u);  // 10.0 and 0.1 (the limits) and 4.0
  EXPECT_EQ(n.ignored, 5u);
  EXPECT_EQ(points.size(), 3u);
  std::vector<Vec2> none;
  const MaskInputCount bad = scanToFloorPoints(view(ranges, std::nan(""), 0.01), RigidTransform(), none);
  EXPECT_EQ(bad.used, 0u);
  EXPECT_EQ(bad.ignored, ranges.size());
  const MaskInputCount empty = scanToFloorPoints(ScanView(), RigidTransform(), none);
  EXPECT_EQ(empty.used + empty.ignored, 0u);
}

TEST(ProjectionMask, CloudPointsBetweenFloorAndHeight)
{
  std::vector<Vec2> points;
  const MaskInputCount n = cloudToFloorPoints(
      {Vec3{1, 1, 0.0}, Vec3{1, 2, 0.5}, Vec3{1, 3, 2.0}, Vec3{1, 4, 2.5}, Vec3{std::nan(""), 0, 1}}, 0.02, 2.0, points);
  EXPECT_EQ(n.used, 2u);
  EXPECT_EQ(n.ignored, 3u);
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].y, 2.0);
  EXPECT_EQ(points[1].y, 3.0);
}

TEST(ProjectionMask, ColumnsContainThePointWithinTheMarginUpToTheHeight)
{
  OccluderMesh mesh;
  mesh.build({Vec2{1.0, -2.0}, Vec2{std::nan(""), 0.0}}, 2.0, 0.1);
  ASSERT_EQ(mesh.columns(), 1u);
  double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9, min_z = 1e9, max_z = -1e9;
  for (const MeshVertex& v : mesh.triangles())
  {
    min_x = std::min(min_x, v.position.x);
    max_x = std::max(max_x, v.position.x);
    min_y = std::min(min_y, v.position.y);
    max_y = std::max(max_y, v.position.y);
    min_z = std::min(min_z, v.position.z);
    max_z = std::max(max_z, v.position.z);
  }
  EXPECT_NEAR(min_x, 0.9, 1e-12);
  EXPECT_NEAR(max_x, 1.1, 1e-12);
  EXPECT_NEAR(min_y, -2.1, 1e-12);
  EXPECT_NEAR(max_y, -1.9, 1e-12);
  EXPECT_EQ(min_z, 0.0);
  EXPECT_EQ(max_z, 2.0);
  // Counter-clockwise seen from outside: each triangle's normal (right-hand rule) is its outward normal.
  const auto& t = mesh.triangles();
  for (std::size_t i = 0; i < t.size(); i += 3)
  {
    const Vec3 a = t[i].position, b = t[i + 1].position, c = t[i + 2].position;
    const Vec3 ab{b.x - a.x, b.y - a.y, b.z - a.z}, ac{c.x - a.x, c.y - a.y, c.z - a.z};
    const Vec3 n{ab.y * ac.z - ab.z * ac.y, ab.z * ac.x - ab.x * ac.z, ab.x * ac.y - ab.y * ac.x};
    EXPECT_GT(n.x * t[i].normal.x + n.y * t[i].normal.y + n.z * t[i].normal.z, 0.0) << "triangle " << i / 3;
  }
}

TEST(ProjectionMask, ThousandPointsAndBadSizes)
{
  std::vector<Vec2> points;
  for (int i = 0; i < 1000; ++i)
  {
    points.push_back(Vec2{0.01 * i, 1.0});
  }
  OccluderMesh mesh;
  mesh.build(points, 2.0, 0.1);
  EXPECT_EQ(mesh.triangles().size(), 1000u * OccluderMesh::kVerticesPerColumn);
  mesh.build(points, 0.0, 0.1);
  EXPECT_TRUE(mesh.triangles().empty());
  mesh.build(points, 2.0, std::nan(""));
  EXPECT_TRUE(mesh.triangles().empty());
}

TEST(ProjectionMask, DenseCloudSnapsToCellCentresSortedAndUnique)
{
  // Cells of 0.1 m: [0, 0.1) x [0, 0.1) has centre (0.05, 0.05); -0.01 falls in [-0.1, 0).
  std::vector<Vec2> points{{0.01, 0.02}, {0.09, 0.08}, {0.05, 0.05}, {-0.01, 0.02}, {0.15, 0.02},
                           {std::nan(""), 0.0}, {1e300, 0.0}};
  EXPECT_TRUE(snapToCells(points, 0.1, 100));
  ASSERT_EQ(points.size(), 3u);
  EXPECT_NEAR(points[0].x, -0.05, 1e-12);
  EXPECT_NEAR(points[0].y, 0.05, 1e-12);
  EXPECT_NEAR(points[1].x, 0.05, 1e-12);
  EXPECT_NEAR(points[1].y, 0.05, 1e-12);
  EXPECT_NEAR(points[2].x, 0.15, 1e-12);
  EXPECT_NEAR(points[2].y, 0.05, 1e-12);
  // A bad cell leaves the points as they are.
  std::vector<Vec2> same{{0.01, 0.02}};
  EXPECT_TRUE(snapToCells(same, 0.0, 100));
  EXPECT_TRUE(snapToCells(same, std::nan(""), 100));
  ASSERT_EQ(same.size(), 1u);
  EXPECT_EQ(same[0].x, 0.01);
}

TEST(ProjectionMask, DenseCloudKeepsTheCellsOfTheFirstPointsUpToTheLimit)
{
  // 300,000 points on a 3 m x 1 m patch (a depth camera's cloud): 30 x 10 cells of 0.1 m.
  std::vector<Vec2> points;
  for (int i = 0; i < 300000; ++i)
  {
    points.push_back(Vec2{0.001 * (i % 3000) + 0.0005, 0.1 * ((i / 3000) % 10) + 0.05});
  }
  std::vector<Vec2> all = points;
  EXPECT_TRUE(snapToCells(all, 0.1, 20000));
  EXPECT_EQ(all.size(), 300u);
  // Limit 5: the cells of the first points in input order (x = 0.0005 .. 0.4995 on row y = 0.05).
  EXPECT_FALSE(snapToCells(points, 0.1, 5));
  ASSERT_EQ(points.size(), 5u);
  for (int k = 0; k < 5; ++k)
  {
    EXPECT_NEAR(points[k].x, 0.05 + 0.1 * k, 1e-9);
    EXPECT_NEAR(points[k].y, 0.05, 1e-9);
  }
}

TEST(ProjectionMask, ACellColumnWithHalfACellMoreMarginCoversEveryPointsOwnColumn)
{
  // Hand check of the display's rule: a point p in a cell of side c with centre q; p's column
  // [p - m, p + m] lies inside q's column [q - m - c/2, q + m + c/2] on each axis.
  const double m = 0.1, c = 0.1;
  for (const Vec2& p : {Vec2{0.0001, 0.0001}, Vec2{0.0999, 0.0999}, Vec2{0.05, 0.0}, Vec2{-0.0001, 0.2}})
  {
    std::vector<Vec2> cell{p};
    ASSERT_TRUE(snapToCells(cell, c, 10));
    OccluderMesh own, wide;
    own.build({p}, 1.0, m);
    wide.build(cell, 1.0, m + 0.5 * c);
    for (const MeshVertex& v : own.triangles())
    {
      double min_x = 1e9, max_x = -1e9, min_y = 1e9, max_y = -1e9;
      for (const MeshVertex& w : wide.triangles())
      {
        min_x = std::min(min_x, w.position.x), max_x = std::max(max_x, w.position.x);
        min_y = std::min(min_y, w.position.y), max_y = std::max(max_y, w.position.y);
      }
      EXPECT_GE(v.position.x, min_x - 1e-12);
      EXPECT_LE(v.position.x, max_x + 1e-12);
      EXPECT_GE(v.position.y, min_y - 1e-12);
      EXPECT_LE(v.position.y, max_y + 1e-12);
    }
  }
}

TEST(ProjectionMask, AppendAddsColumnsOfItsOwnMargin)
{
  OccluderMesh mesh;
  mesh.build({Vec2{0.0, 0.0}}, 2.0, 0.1);
  mesh.append({Vec2{1.0, 0.0}}, 2.0, 0.3);
  ASSERT_EQ(mesh.columns(), 2u);
  double max_x = -1e9;
  for (const MeshVertex& v : mesh.triangles())
  {
    max_x = std::max(max_x, v.position.x);
  }
  EXPECT_NEAR(max_x, 1.3, 1e-12);
  mesh.clear();
  EXPECT_EQ(mesh.columns(), 0u);
}

namespace
{
/// A symmetric OpenGL perspective: 90 degrees field of view, square, near 0.1, far 100.
std::array<double, 16> perspective()
{
  const double n = 0.1, f = 100.0;
  return {1, 0, 0, 0,  0, 1, 0, 0,  0, 0, -(f + n) / (f - n), -2 * f * n / (f - n),  0, 0, -1, 0};
}

std::array<double, 4> clip(const std::array<double, 16>& m, double x, double y, double z)
{
  std::array<double, 4> out{};
  for (int r = 0; r < 4; ++r)
  {
    out[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3];
  }
  return out;
}

bool visible(const std::array<double, 4>& c)
{
  return c[3] > 0 && std::abs(c[0]) <= c[3] && std::abs(c[1]) <= c[3] && c[2] >= -c[3] && c[2] <= c[3];
}
}  // namespace

TEST(ObliqueNearPlane, ClipsWhatLiesBeyondThePlaneOnly)
{
  // Camera 2 m above the floor looking straight down: camera -z is world down, camera y is world
  // +x (any). Max lit height 1 m is the plane "camera z >= -1" i.e. (0, 0, -1, -1).(x, y, z, 1) >= 0
  // -> -z - 1 >= 0 -> z <= -1 (at least 1 m below the camera: at most 1 m above the floor).
  std::array<double, 16> m = perspective();
  const std::array<double, 16> original = m;
  ASSERT_TRUE(applyObliqueNearPlane(m, {0, 0, -1, -1}));
  // On the floor (2 m below) and at 0.5 m above it: visible, at the same pixels as before.
  for (double depth : {2.0, 1.5, 1.01})
  {
    for (double x : {-0.5 * depth, 0.0, 0.3 * depth})
    {
      const auto a = clip(m, x, 0.2, -depth), b = clip(original, x, 0.2, -depth);
      EXPECT_TRUE(visible(a)) << "depth " << depth << " x " << x;
      EXPECT_NEAR(a[0] / a[3], b[0] / b[3], 1e-12);
      EXPECT_NEAR(a[1] / a[3], b[1] / b[3], 1e-12);
    }
  }
  // Above 1 m (less than 1 m below the camera): clipped, though inside the original frustum.
  for (double depth : {0.99, 0.5, 0.2})
  {
    EXPECT_TRUE(visible(clip(original, 0.0, 0.0, -depth)));
    EXPECT_FALSE(visible(clip(m, 0.0, 0.0, -depth))) << "depth " << depth;
  }
}

TEST(ObliqueNearPlane, TiltedPlaneAndCameraOnTheWrongSide)
{
  std::array<double, 16> m = perspective();
  // A tilted plane 1 m ahead: keep points with (x + z) <= -1 ... i.e. -(x + z) - 1 >= 0.
  ASSERT_TRUE(applyObliqueNearPlane(m, {-1, 0, -1, -1}));
  EXPECT_TRUE(visible(clip(m, 0.0, 0.0, -3.0)));
  EXPECT_FALSE(visible(clip(m, 0.0, 0.0, -0.5)));
  EXPECT_TRUE(visible(clip(m, 0.4, 0.0, -3.0)));
  // The camera on the visible side (d >= 0): refused, matrix untouched.
  std::array<double, 16> n = perspective();
  EXPECT_FALSE(applyObliqueNearPlane(n, {0, 0, -1, 1}));
  EXPECT_EQ(n, perspective());
  EXPECT_FALSE(applyObliqueNearPlane(n, {0, 0, std::nan(""), -1}));
}
