// FloorFootprint: where the projector's image lands on the floor.
#include <gtest/gtest.h>

#include <cmath>

#include "optical_orientation.h"
#include "rviz_projector/core/floor_footprint.h"

using rviz_projector::FloorFootprint;
using rviz_projector::PinholeModel;
using rviz_projector::RigidTransform;
using rviz_projector::Vec2;
using rviz_projector::Vec3;

namespace
{
/// Optical frame looking straight down from `height`: optical x = world x, optical y = world -y.
RigidTransform lookingDown(double height) { return RigidTransform::fromQuaternion(1, 0, 0, 0, {0, 0, height}); }

/// Optical frame pitched down by `pitch` from horizontal, looking along world +x.
RigidTransform pitchedDown(double pitch, double height)
{
  const rviz_projector_test::Quaternion q = rviz_projector_test::opticalOrientation(0.0, pitch, 0.0);
  return RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, {0, 0, height});
}
}  // namespace

TEST(FloorFootprint, StraightDownIsARectangle)
{
  PinholeModel lens(1280, 800, 1000, 1000, 639.5, 399.5);
  FloorFootprint f(lens, lookingDown(1.2), 20.0);
  ASSERT_TRUE(f.complete());
  // Half-widths at the pixel edges: 640 / 1000 and 400 / 1000 per metre of height.
  EXPECT_NEAR(f.width(), 2 * 0.64 * 1.2, 1e-9);
  EXPECT_NEAR(f.depth(), 2 * 0.40 * 1.2, 1e-9);
  EXPECT_NEAR(f.throwDistance(), 1.2, 1e-9);
  // Top-left pixel corner: optical (-0.64, -0.4) -> world (-0.768, +0.48).
  EXPECT_NEAR(f.corners()[0].x, -0.768, 1e-9);
  EXPECT_NEAR(f.corners()[0].y, 0.48, 1e-9);
  EXPECT_NEAR(f.corners()[0].z, 0.0, 1e-12);
}

TEST(FloorFootprint, CornersProjectBackToTheImageCorners)
{
  PinholeModel lens(1280, 800, 1900, 1900, 640, 817);
  const RigidTransform pose = pitchedDown(0.9, 1.2);
  FloorFootprint f(lens, pose, 50.0);
  ASSERT_TRUE(f.complete());
  const Vec2 expected[] = {{-0.5, -0.5}, {1279.5, -0.5}, {1279.5, 799.5}, {-0.5, 799.5}};
  // World -> optical: inverse of the pose (rotation transpose).
  const auto& R = pose.rotation();
  for (int i = 0; i < 4; ++i)
  {
    const Vec3 d = f.corners()[i] - pose.translation();
    const Vec3 optical{R[0] * d.x + R[3] * d.y + R[6] * d.z, R[1] * d.x + R[4] * d.y + R[7] * d.z,
                       R[2] * d.x + R[5] * d.y + R[8] * d.z};
    Vec2 px;
    ASSERT_TRUE(lens.project(optical, px));
    EXPECT_NEAR(px.x, expected[i].x, 1e-6);
    EXPECT_NEAR(px.y, expected[i].y, 1e-6);
  }
  // The bottom of the image (larger v) is nearer the robot: trapezoid, wider at the far (top) edge.
  EXPECT_GT(f.corners()[0].x, f.corners()[3].x);
  EXPECT_GT(std::abs(f.corners()[0].y - f.corners()[1].y), std::abs(f.corners()[3].y - f.corners()[2].y));
}

TEST(FloorFootprint, RaysAboveTheHorizonEndAtMaxDistance)
{
  PinholeModel lens(1280, 800, 1000, 1000, 639.5, 399.5);
  FloorFootprint f(lens, pitchedDown(0.1, 1.2), 8.0);
  EXPECT_FALSE(f.complete());
  EXPECT_NEAR(rviz_projector::norm(f.corners()[0] - f.origin()), 8.0, 1e-9);  // top edge: sky
  EXPECT_NEAR(f.corners()[3].z, 0.0, 1e-9);                                   // bottom edge: floor
  FloorFootprint up(lens, pitchedDown(-0.5, 1.2), 8.0);
  EXPECT_LT(up.throwDistance(), 0.0);
}

TEST(FloorFootprint, ThroughABarrelLensTheOutlineFollowsTheUndistortedRays)
{
  // Looking straight down from 1 m: a ray (x, y, 1) meets the floor at world (x, -y). The lens
  // k1 = -0.2, k2 = 0.05 sends the ideal ray r to the raw pixel at r (1 - 0.2 r^2 + 0.05 r^4); the
  // outline's points are the floor points of the rays that land on the image's outer edge.
  const PinholeModel lens(1280, 800, 1900, 1900, 639.5, 399.5);
  const rviz_projector::LensDistortion wide(rviz_projector::LensDistortion::Model::PlumbBob, {-0.2, 0.05, 0, 0, 0});
  const FloorFootprint pinhole(lens, lookingDown(1.0), 20.0);
  const FloorFootprint f(lens, lookingDown(1.0), 20.0, wide);
  ASSERT_TRUE(f.complete());
  ASSERT_EQ(f.outline().size(), 4u * FloorFootprint::kEdgePoints);
  const auto radial = [](double r) { return r * (1 - 0.2 * r * r + 0.05 * r * r * r * r); };
  for (std::size_t i = 0; i < f.outline().size(); ++i)
  {
    // Each outline point, seen through the lens formula, lands on the image edge: a raw pixel
    // with u = -0.5 or 1279.5, or v = -0.5 or 799.5.
    const Vec3& p = f.outline()[i];
    const double x = p.x, y = -p.y;  // the ray (x, y, 1)
    const double r = std::hypot(x, y);
    const double scale = radial(r) / r;
    const double u = 639.5 + 1900 * x * scale;
    const double v = 399.5 + 1900 * y * scale;
    const double to_edge = std::min({std::abs(u + 0.5), std::abs(u - 1279.5), std::abs(v + 0.5), std::abs(v - 799.5)});
    EXPECT_LT(to_edge, 1e-6) << "outline point " << i << " lands on raw pixel (" << u << ", " << v << ")";
    // Beyond the pinhole's outline where the lens reaches further (a barrel lens at its corners).
    EXPECT_GE(std::hypot(p.x, p.y), std::hypot(pinhole.outline()[i].x, pinhole.outline()[i].y) - 1e-9);
  }
  // The top edge is a curve: its middle point is nearer the centre line than the chord's.
  const Vec3& left = f.outline()[0];
  const Vec3& middle = f.outline()[FloorFootprint::kEdgePoints / 2];
  const Vec3& right = f.outline()[FloorFootprint::kEdgePoints];
  EXPECT_NEAR(left.y, right.y, 1e-9) << "a centred lens: the top edge's ends are level";
  EXPECT_LT(std::abs(middle.y), std::abs(left.y)) << "a barrel lens bows the lit edge outwards at the corners";
  // The pinhole's outline is the rectangle: its edge points lie on the straight edges.
  for (int k = 0; k < FloorFootprint::kEdgePoints; ++k)
  {
    EXPECT_NEAR(pinhole.outline()[k].y, pinhole.corners()[0].y, 1e-9);
  }
}
