// PinholeModel: CameraInfo semantics, pixel convention and the OpenGL projection matrix.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rviz_projector/core/pinhole_model.h"

using rviz_projector::LensCalibration;
using rviz_projector::LensCheck;
using rviz_projector::PinholeModel;
using rviz_projector::Vec2;
using rviz_projector::Vec3;

namespace
{
LensCalibration calibration(std::uint32_t w, std::uint32_t h, double fx, double fy, double cx, double cy)
{
  LensCalibration c;
  c.width = w;
  c.height = h;
  c.K = {fx, 0, cx, 0, fy, cy, 0, 0, 1};
  c.P = {fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0};
  return c;
}

/// Pixel (OpenCV convention) where OpenGL puts a point given in the optical frame.
Vec2 glPixel(const PinholeModel& m, const Vec3& optical)
{
  const auto M = m.glProjectionMatrix(0.1, 100.0);
  const double p[4] = {optical.x, -optical.y, -optical.z, 1.0};  // optical -> OpenGL camera frame
  double clip[4];
  for (int r = 0; r < 4; ++r)
  {
    clip[r] = M[4 * r] * p[0] + M[4 * r + 1] * p[1] + M[4 * r + 2] * p[2] + M[4 * r + 3] * p[3];
  }
  const double x_window = (clip[0] / clip[3] + 1.0) * 0.5 * m.width();
  const double y_window = (clip[1] / clip[3] + 1.0) * 0.5 * m.height();  // up from the bottom
  return {x_window - 0.5, m.height() - y_window - 0.5};
}
}  // namespace

TEST(PinholeModel, ProjectsWithPAndOpenCvPixelCentres)
{
  PinholeModel m;
  ASSERT_TRUE(PinholeModel::fromCalibration(calibration(1280, 800, 1900, 1900, 640, 817), m).ok());
  Vec2 px;
  ASSERT_TRUE(m.project({0.0, 0.0, 2.0}, px));
  EXPECT_DOUBLE_EQ(px.x, 640.0);
  EXPECT_DOUBLE_EQ(px.y, 817.0);
  ASSERT_TRUE(m.project({0.1, -0.2, 2.0}, px));
  EXPECT_DOUBLE_EQ(px.x, 640.0 + 1900 * 0.05);
  EXPECT_DOUBLE_EQ(px.y, 817.0 - 1900 * 0.1);
  EXPECT_FALSE(m.project({0.0, 0.0, -1.0}, px));
  EXPECT_FALSE(m.project({0.0, 0.0, 0.0}, px));
}

TEST(PinholeModel, RayIsTheInverseOfProject)
{
  PinholeModel m(1280, 800, 1500, 1400, 600.25, 750.5);
  const Vec3 p{0.3, -0.4, 2.5};
  Vec2 px;
  ASSERT_TRUE(m.project(p, px));
  const Vec3 r = m.ray(px);
  EXPECT_NEAR(r.x * p.z, p.x, 1e-12);
  EXPECT_NEAR(r.y * p.z, p.y, 1e-12);
  EXPECT_DOUBLE_EQ(r.z, 1.0);
}

TEST(PinholeModel, ReferenceProjectorUsesPNotK)
{
  // The reference calibration: cy = 817 in K, 750 in P. Renderers use P.
  LensCalibration c = calibration(1280, 800, 1900, 1900, 640, 817);
  c.P[6] = 750;
  PinholeModel m;
  ASSERT_TRUE(PinholeModel::fromCalibration(c, m).ok());
  EXPECT_DOUBLE_EQ(m.cy(), 750.0);
  c.P.fill(0.0);  // all-zero P: fall back to K
  ASSERT_TRUE(PinholeModel::fromCalibration(c, m).ok());
  EXPECT_DOUBLE_EQ(m.cy(), 817.0);
  EXPECT_DOUBLE_EQ(m.tx(), 0.0);
}

TEST(PinholeModel, GlMatrixLandsOnThePredictedPixel)
{
  const PinholeModel models[] = {PinholeModel(1280, 800, 1000, 1000, 639.5, 399.5),
                                 PinholeModel(1280, 800, 1900, 1900, 640, 817),
                                 PinholeModel(1281, 721, 800, 950, 100.25, -30.0, 12.0, -7.0)};
  for (const PinholeModel& m : models)
  {
    for (const Vec3& p : {Vec3{0, 0, 1}, Vec3{0.2, -0.1, 1.5}, Vec3{-0.4, 0.3, 3.0}, Vec3{1.0, 1.0, 10.0}})
    {
      Vec2 expected;
      ASSERT_TRUE(m.project(p, expected));
      const Vec2 gl = glPixel(m, p);
      EXPECT_NEAR(gl.x, expected.x, 1e-9);
      EXPECT_NEAR(gl.y, expected.y, 1e-9);
    }
  }
}

TEST(PinholeModel, GlMatrixMapsPixelEdgesToTheViewportEdges)
{
  // The centre of pixel (0, 0) is half a pixel inside the top-left corner of the viewport.
  PinholeModel m(640, 480, 500, 500, 319.5, 239.5);
  const Vec3 top_left_centre = m.ray({0.0, 0.0});
  const Vec2 gl = glPixel(m, top_left_centre);
  EXPECT_NEAR(gl.x, 0.0, 1e-9);
  EXPECT_NEAR(gl.y, 0.0, 1e-9);
}

TEST(PinholeModel, BinningAndRegionOfInterest)
{
  LensCalibration c = calibration(1280, 800, 1000, 1000, 640, 400);
  c.binning_x = 2;
  c.binning_y = 2;
  PinholeModel binned;
  ASSERT_TRUE(PinholeModel::fromCalibration(c, binned).ok());
  EXPECT_EQ(binned.width(), 640u);
  EXPECT_EQ(binned.height(), 400u);
  PinholeModel full(1280, 800, 1000, 1000, 640, 400);
  Vec2 u_full, u_binned;
  ASSERT_TRUE(full.project({0.3, 0.2, 2.0}, u_full));
  ASSERT_TRUE(binned.project({0.3, 0.2, 2.0}, u_binned));
  // CameraInfo's binning (as image_geometry applies it) divides pixel coordinates: u / 2.
  EXPECT_NEAR(u_binned.x, u_full.x / 2, 1e-12);
  EXPECT_NEAR(u_binned.y, u_full.y / 2, 1e-12);
  EXPECT_DOUBLE_EQ(binned.cx(), 320.0);
  EXPECT_DOUBLE_EQ(binned.fx(), 500.0);

  c.binning_x = c.binning_y = 0;
  c.roi_x_offset = 100;
  c.roi_y_offset = 50;
  c.roi_width = 400;
  c.roi_height = 300;
  PinholeModel roi;
  ASSERT_TRUE(PinholeModel::fromCalibration(c, roi).ok());
  EXPECT_EQ(roi.width(), 400u);
  EXPECT_DOUBLE_EQ(roi.cx(), 540.0);
  c.roi_width = 2000;
  EXPECT_NE(PinholeModel::fromCalibration(c, roi).error.find("region of interest"), std::string::npos);
}

TEST(PinholeModel, BadCalibrationsAreRefusedWithAReason)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  PinholeModel m(10, 10, 1, 1, 5, 5);
  struct Case
  {
    LensCalibration calibration;
    const char* expected;
  };
  LensCalibration zero_width = calibration(0, 800, 1000, 1000, 640, 400);
  LensCalibration nan_p = calibration(1280, 800, 1000, 1000, 640, 400);
  nan_p.P[2] = nan;
  LensCalibration nan_k = calibration(1280, 800, 1000, 1000, 640, 400);
  nan_k.P.fill(0.0);
  nan_k.K[4] = nan;
  LensCalibration negative_f = calibration(1280, 800, -1000, 1000, 640, 400);
  LensCalibration zero_f = calibration(1280, 800, 0, 0, 640, 400);
  zero_f.P[10] = 1;
  LensCalibration all_zero = calibration(1280, 800, 0, 0, 0, 0);
  all_zero.K.fill(0.0);
  all_zero.P.fill(0.0);
  LensCalibration huge = calibration(20000, 20000, 1000, 1000, 640, 400);
  LensCalibration nan_d = calibration(1280, 800, 1000, 1000, 640, 400);
  nan_d.D = {0.0, nan};
  const Case cases[] = {{zero_width, "image size is 0x800"},
                        {nan_p, "P[2] is not finite"},
                        {nan_k, "K[4] is not finite"},
                        {negative_f, "focal length in P is not positive"},
                        {zero_f, "focal length in P is not positive"},
                        {all_zero, "P and K are all zero"},
                        {huge, "exceeds the 16384x16384 limit"},
                        {nan_d, "D[1] is not finite"}};
  for (const Case& c : cases)
  {
    const LensCheck check = PinholeModel::fromCalibration(c.calibration, m);
    EXPECT_FALSE(check.ok()) << c.expected;
    EXPECT_NE(check.error.find(c.expected), std::string::npos) << check.error;
    EXPECT_EQ(m.width(), 10u) << "model must stay unchanged on error";
  }
}

TEST(PinholeModel, DistortionIsReportedNotAppliedOnlyForModelsThatAreNotDrawn)
{
  LensCalibration c = calibration(1280, 800, 1000, 1000, 640, 400);
  c.distortion_model = "plumb_bob";
  c.D = {0, 0, 0, 0, 0};
  PinholeModel m;
  LensCheck check = PinholeModel::fromCalibration(c, m);
  EXPECT_TRUE(check.ok());
  EXPECT_TRUE(check.warning.empty());
  c.D = {0.1, -0.02, 0, 0, 0};  // plumb_bob: the ProjectorCamera draws it (issue 24)
  check = PinholeModel::fromCalibration(c, m);
  EXPECT_TRUE(check.ok());
  EXPECT_TRUE(check.warning.empty()) << check.warning;
  c.distortion_model = "equidistant";  // not modelled: the view is the ideal pinhole
  c.D = {0.1, -0.02, 0, 0};
  check = PinholeModel::fromCalibration(c, m);
  EXPECT_TRUE(check.ok());
  EXPECT_NE(check.warning.find("distortion D is not applied"), std::string::npos);
  c.D.clear();
  c.distortion_model = "fisheye_magic";
  check = PinholeModel::fromCalibration(c, m);
  EXPECT_NE(check.warning.find("unknown distortion_model 'fisheye_magic'"), std::string::npos);
}
