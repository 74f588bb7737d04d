// PinholeModel against an independent oracle, image_geometry::PinholeCameraModel: the same
// CameraInfo must project to the same pixel (<= 0.05 px) and back to the same ray, including
// Tx/Ty, binning and a region of interest; and the model's image size is image_geometry's reduced
// resolution (the ROI's size divided by the binning).
#include <gtest/gtest.h>

#include <image_geometry/pinhole_camera_model.h>
#include <sensor_msgs/CameraInfo.h>

#include <string>
#include <vector>

#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/ros/ros_conversions.h"

using rviz_projector::LensCalibration;
using rviz_projector::PinholeModel;
using rviz_projector::Vec2;
using rviz_projector::Vec3;

namespace
{
constexpr double kTolerancePx = 0.05;

/// The reference projector (1280x800, cy in K differs from P) with a few knobs.
sensor_msgs::CameraInfo referenceInfo()
{
  sensor_msgs::CameraInfo info;
  info.width = 1280;
  info.height = 800;
  info.distortion_model = "plumb_bob";
  info.D = {0.0, 0.0, 0.0, 0.0, 0.0};
  info.K = {1900.0, 0.0, 641.3, 0.0, 1890.0, 817.0, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {1905.5, 0.0, 639.7, 0.0, 0.0, 1895.25, 750.4, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

/// The conversion the display uses (ros_conversions): the CameraInfo's fields, nothing computed.
LensCalibration toCalibration(const sensor_msgs::CameraInfo& info)
{
  return rviz_projector::toLensCalibration(info);
}

/// Points in front of the lens spread over (and beyond) the image, near and far.
std::vector<Vec3> samplePoints()
{
  std::vector<Vec3> points;
  for (double z : {0.3, 1.0, 2.5, 7.0})
  {
    for (double x = -0.6; x <= 0.6; x += 0.15)
    {
      for (double y = -0.5; y <= 0.5; y += 0.125)
      {
        points.push_back({x * z, y * z, z});
      }
    }
  }
  return points;
}

/// Compares projections and rays of PinholeModel with image_geometry for one CameraInfo.
void expectSameAsImageGeometry(const sensor_msgs::CameraInfo& info, const sensor_msgs::CameraInfo& oracle_info)
{
  image_geometry::PinholeCameraModel oracle;
  ASSERT_TRUE(oracle.fromCameraInfo(oracle_info));
  PinholeModel model;
  const auto check = PinholeModel::fromCalibration(toCalibration(info), model);
  ASSERT_TRUE(check.ok()) << check.error;

  const cv::Size reduced = oracle.reducedResolution();
  EXPECT_EQ(model.width(), static_cast<std::uint32_t>(reduced.width));
  EXPECT_EQ(model.height(), static_cast<std::uint32_t>(reduced.height));

  int compared = 0;
  for (const Vec3& p : samplePoints())
  {
    const cv::Point2d expected = oracle.project3dToPixel(cv::Point3d(p.x, p.y, p.z));
    Vec2 px;
    ASSERT_TRUE(model.project(p, px));
    ASSERT_NEAR(px.x, expected.x, kTolerancePx) << "point " << p.x << ", " << p.y << ", " << p.z;
    ASSERT_NEAR(px.y, expected.y, kTolerancePx) << "point " << p.x << ", " << p.y << ", " << p.z;
    ++compared;
  }
  EXPECT_GT(compared, 100);

  // image_geometry's ray through a pixel is the point at depth 1 that projects there (Tx/Ty
  // included); PinholeModel's is a direction from its optical centre: centre + ray is that point.
  for (double u = -100.0; u <= model.width() + 100.0; u += 97.5)
  {
    for (double v = -100.0; v <= model.height() + 100.0; v += 83.25)
    {
      const cv::Point3d expected = oracle.projectPixelTo3dRay(cv::Point2d(u, v));
      ASSERT_NEAR(expected.z, 1.0, 1e-12) << "image_geometry's rays are expected at z = 1";
      const Vec3 c = model.centre();
      const Vec3 r = model.ray({u, v});
      // Angles: 1e-5 at depth 1 is far below 0.05 px at these focal lengths.
      ASSERT_NEAR(c.x + r.x * r.z, expected.x, 1e-5) << "pixel " << u << ", " << v;
      ASSERT_NEAR(c.y + r.y * r.z, expected.y, 1e-5) << "pixel " << u << ", " << v;
      ASSERT_DOUBLE_EQ(r.z, 1.0);
    }
  }
}

void expectSameAsImageGeometry(const sensor_msgs::CameraInfo& info)
{
  expectSameAsImageGeometry(info, info);
}
}  // namespace

TEST(PinholeOracle, Plain)
{
  expectSameAsImageGeometry(referenceInfo());
}

TEST(PinholeOracle, TxAndTy)
{
  sensor_msgs::CameraInfo info = referenceInfo();
  info.P[3] = -95.3;  // Tx = -fx * baseline
  info.P[7] = 41.7;
  expectSameAsImageGeometry(info);
}

TEST(PinholeOracle, Binning2x2)
{
  sensor_msgs::CameraInfo info = referenceInfo();
  info.binning_x = 2;
  info.binning_y = 2;
  expectSameAsImageGeometry(info);
}

TEST(PinholeOracle, Binning2x1WithTx)
{
  sensor_msgs::CameraInfo info = referenceInfo();
  info.binning_x = 2;
  info.binning_y = 1;
  info.P[3] = -95.3;
  info.P[7] = 12.5;
  expectSameAsImageGeometry(info);
}

TEST(PinholeOracle, Binning3x4OddSize)
{
  sensor_msgs::CameraInfo info = referenceInfo();
  info.width = 1281;
  info.height = 803;
  info.binning_x = 3;
  info.binning_y = 4;
  expectSameAsImageGeometry(info);
}

TEST(PinholeOracle, RegionOfInterest)
{
  sensor_msgs::CameraInfo info = referenceInfo();
  info.roi.x_offset = 200;
  info.roi.y_offset = 150;
  info.roi.width = 640;
  info.roi.height = 400;
  expectSameAsImageGeometry(info);
}

TEST(PinholeOracle, RegionOfInterestAtTheOrigin)
{
  // Offsets zero, size smaller: the reduced image is the ROI's size, the principal point stays.
  sensor_msgs::CameraInfo info = referenceInfo();
  info.roi.width = 500;
  info.roi.height = 300;
  expectSameAsImageGeometry(info);
}

TEST(PinholeOracle, RegionOfInterestAndBinning)
{
  sensor_msgs::CameraInfo info = referenceInfo();
  info.roi.x_offset = 201;
  info.roi.y_offset = 99;
  info.roi.width = 641;
  info.roi.height = 401;
  info.binning_x = 2;
  info.binning_y = 2;
  info.P[3] = 30.0;
  expectSameAsImageGeometry(info);
}

TEST(PinholeOracle, AllZeroPUsesK)
{
  // image_geometry has no fallback for an all-zero P (it would project everything to cx = 0):
  // the oracle gets P = [K | 0], which is what CameraInfo's K means for an unrectified camera.
  sensor_msgs::CameraInfo info = referenceInfo();
  info.P.fill(0.0);
  sensor_msgs::CameraInfo oracle_info = info;
  oracle_info.P = {info.K[0], info.K[1], info.K[2], 0.0, info.K[3], info.K[4], info.K[5], 0.0,
                   info.K[6], info.K[7], info.K[8], 0.0};
  expectSameAsImageGeometry(info, oracle_info);
  // ... with binning and an ROI on top.
  info.binning_x = oracle_info.binning_x = 2;
  info.binning_y = oracle_info.binning_y = 2;
  info.roi.x_offset = oracle_info.roi.x_offset = 100;
  info.roi.y_offset = oracle_info.roi.y_offset = 60;
  info.roi.width = oracle_info.roi.width = 1000;
  info.roi.height = oracle_info.roi.height = 700;
  expectSameAsImageGeometry(info, oracle_info);
}

TEST(PinholeOracle, KIsNotUsedWhenPIsSet)
{
  // Guard for the test above: with P set, K's different numbers must not matter.
  sensor_msgs::CameraInfo info = referenceInfo();
  sensor_msgs::CameraInfo oracle_info = info;
  oracle_info.K = {1.0, 0.0, 2.0, 0.0, 3.0, 4.0, 0.0, 0.0, 1.0};
  expectSameAsImageGeometry(info, oracle_info);
}
