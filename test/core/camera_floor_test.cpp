// Camera pixels on the floor (hand-computed cases) and structured-light correspondences judged by
// the true projector of an independent simulation (test/core/structured_light_sim.h).
#include "rviz_projector/core/camera_floor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "structured_light_sim.h"

namespace rviz_projector
{
namespace
{
LensCalibration simpleCamera(double k1)
{
  sim::Lens lens{640, 480, 500.0, 500.0, 320.0, 240.0, {k1, 0.0, 0.0, 0.0, 0.0}};
  return sim::calibrationOf(lens);
}

/// Camera at (1, 2, 1.5) looking straight down, image x along base x (image y along base -y).
RigidTransform lookingDown()
{
  return RigidTransform::fromMatrix({1, 0, 0, 0, -1, 0, 0, 0, -1}, Vec3{1.0, 2.0, 1.5});
}

TEST(CameraFloor, StraightDownByHand)
{
  std::string error;
  const double k1 = -0.1;
  // Normalised radius 0.1 along x is drawn at 0.1 (1 + k1 0.01) (plumb_bob) -> pixel 320 + 500 that.
  const double distorted = 0.1 * (1.0 + k1 * 0.01);
  const std::vector<Vec3> points = cameraPixelsOnPlane(simpleCamera(k1), lookingDown(),
                                                       {{320.0, 240.0}, {320.0 + 500.0 * distorted, 240.0},
                                                        {320.0, 240.0 + 500.0 * distorted}},
                                                       0.0, error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_EQ(points.size(), 3u);
  EXPECT_NEAR(points[0].x, 1.0, 1e-9);
  EXPECT_NEAR(points[0].y, 2.0, 1e-9);
  EXPECT_EQ(points[0].z, 0.0);
  EXPECT_NEAR(points[1].x, 1.0 + 0.15, 1e-8);  // 1.5 m x 0.1
  EXPECT_NEAR(points[1].y, 2.0, 1e-8);
  EXPECT_NEAR(points[2].x, 1.0, 1e-8);
  EXPECT_NEAR(points[2].y, 2.0 - 0.15, 1e-8);  // image down = base -y
  // Another plane: 0.5 m up, the camera 1 m above it.
  const std::vector<Vec3> raised =
      cameraPixelsOnPlane(simpleCamera(k1), lookingDown(), {{320.0 + 500.0 * distorted, 240.0}}, 0.5, error);
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_NEAR(raised[0].x, 1.1, 1e-8);
  EXPECT_EQ(raised[0].z, 0.5);
}

TEST(CameraFloor, RaysThatMissThePlaneAreNaN)
{
  // Looking horizontally along base x from 1 m up: the centre row is parallel, rows above it point
  // up (the plane is behind them), rows below reach the floor at 1 / tan.
  const RigidTransform horizontal = RigidTransform::fromMatrix({0, 0, 1, -1, 0, 0, 0, -1, 0}, Vec3{0, 0, 1.0});
  std::string error;
  const std::vector<Vec3> points = cameraPixelsOnPlane(
      simpleCamera(0.0), horizontal, {{320.0, 240.0}, {320.0, 100.0}, {320.0, 290.0}, {std::nan(""), 3.0}}, 0.0,
      error);
  ASSERT_TRUE(error.empty()) << error;
  ASSERT_EQ(points.size(), 4u);
  EXPECT_FALSE(isFinite(points[0]));
  EXPECT_FALSE(isFinite(points[1]));
  EXPECT_NEAR(points[2].x, 1.0 / 0.1, 1e-9);  // 50 px below centre at f = 500: slope 0.1
  EXPECT_FALSE(isFinite(points[3]));
}

TEST(CameraFloor, BadLensesAndPosesAreRefused)
{
  std::string error;
  LensCalibration camera = simpleCamera(-0.1);
  camera.K[0] = std::nan("");
  EXPECT_TRUE(cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error).empty());
  EXPECT_NE(error.find("K is not finite"), std::string::npos) << error;
  camera = simpleCamera(-0.1);
  camera.K[4] = 0.0;
  cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error);
  EXPECT_NE(error.find("not positive"), std::string::npos) << error;
  camera = simpleCamera(-0.1);
  camera.K[1] = 0.5;
  cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error);
  EXPECT_NE(error.find("skew"), std::string::npos) << error;
  camera = simpleCamera(-0.1);
  camera.binning_x = 2;
  cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error);
  EXPECT_NE(error.find("binning"), std::string::npos) << error;
  camera = simpleCamera(-0.1);
  camera.roi_width = 320;
  camera.roi_height = 240;
  cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error);
  EXPECT_NE(error.find("region of interest"), std::string::npos) << error;
  camera.roi_width = 640;  // the whole image: fine
  camera.roi_height = 480;
  cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error);
  EXPECT_TRUE(error.empty()) << error;
  camera = simpleCamera(-0.1);
  camera.D[1] = std::numeric_limits<double>::infinity();
  cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error);
  EXPECT_NE(error.find("distortion"), std::string::npos) << error;
  camera = simpleCamera(-0.1);
  camera.D = {-0.9, 0.0, 0.0, 0.0, 0.0};  // folds before the corner (normalised radius 0.8)
  cameraPixelsOnPlane(camera, lookingDown(), {{1, 1}}, 0.0, error);
  EXPECT_NE(error.find("distortion"), std::string::npos) << error;
  cameraPixelsOnPlane(simpleCamera(0.0), RigidTransform::fromMatrix({1, 0, 0, 0, 1, 0, 0, 0, 1}, Vec3{0, std::nan(""), 1}),
                      {{1, 1}}, 0.0, error);
  EXPECT_NE(error.find("not finite"), std::string::npos) << error;
  cameraPixelsOnPlane(simpleCamera(0.0), lookingDown(), {{1, 1}}, std::nan(""), error);
  EXPECT_NE(error.find("plane"), std::string::npos) << error;
}

struct Measured
{
  double median = 0.0;
  double max = 0.0;
  double p99 = 0.0;
  std::size_t points = 0;
  double coverage = 0.0;
  double decode_ms = 0.0;
  double correspond_ms = 0.0;
};

/// Correspondences of the simulated camera, judged by the true projector.
Measured runScene(const sim::Scene& scene, const sim::Camera& camera, const CorrespondenceOptions& options,
                  const RigidTransform& camera_pose)
{
  const std::vector<PatternFrame> frames = grayCodeFrames(scene.projector.width, scene.projector.height);
  std::vector<cv::Mat> captures;
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    captures.push_back(camera.capture(frames[i].image, 1000 + i));
  }
  Measured m;
  const auto t0 = std::chrono::steady_clock::now();
  const GrayDecodeResult decoded = decodeGrayCode(scene.projector.width, scene.projector.height, captures);
  const auto t1 = std::chrono::steady_clock::now();
  const Correspondences c = floorCorrespondences(decoded, sim::calibrationOf(scene.camera), camera_pose,
                                                 scene.projector.width, scene.projector.height, options);
  const auto t2 = std::chrono::steady_clock::now();
  m.decode_ms = std::chrono::duration<double, std::milli>(t1 - t0).count();
  m.correspond_ms = std::chrono::duration<double, std::milli>(t2 - t1).count();
  EXPECT_TRUE(decoded.error.empty()) << decoded.error;
  EXPECT_TRUE(c.error.empty()) << c.error;
  std::vector<cv::Point3d> world;
  for (const FloorPoint& p : c.points)
  {
    world.emplace_back(p.world.x, p.world.y, p.world.z);
  }
  m.points = c.points.size();
  m.coverage = c.coverage;
  if (world.empty())
  {
    return m;
  }
  const std::vector<cv::Point2d> truth = sim::projectWithProjector(scene, world);
  std::vector<double> errors;
  for (std::size_t i = 0; i < truth.size(); ++i)
  {
    errors.push_back(std::hypot(truth[i].x - c.points[i].pixel.x, truth[i].y - c.points[i].pixel.y));
  }
  std::sort(errors.begin(), errors.end());
  m.median = errors[errors.size() / 2];
  m.max = errors.back();
  m.p99 = errors[errors.size() * 99 / 100];
  std::printf("[          ] lit %d decoded %d full %d; %zu correspondences (coverage %.2f, %d samples, %d rejected); "
              "projector px error median %.3f, 99%% %.3f, max %.3f; decode %.1f ms, correspondences %.1f ms "
              "(%zu frames of %dx%d)\n",
              decoded.lit, decoded.decoded, decoded.full, c.points.size(), c.coverage, c.samples, c.rejected,
              m.median, m.p99, m.max, m.decode_ms, m.correspond_ms, captures.size(),
              captures[0].cols, captures[0].rows);
  return m;
}

class SimulatedCorrespondences : public ::testing::TestWithParam<bool>
{
};

TEST_P(SimulatedCorrespondences, FloorPointsLandOnTheirProjectorPixels)
{
  const sim::Scene scene = sim::demoScene(GetParam());
  const sim::Camera& camera = sim::demoCamera(GetParam());
  const RigidTransform pose = sim::transformOf(scene.camera_pose);
  const Measured fitted = runScene(scene, camera, CorrespondenceOptions(), pose);
  // Measured (pinhole / wide angle): coverage 0.29 / 0.37 (the camera is ~4x coarser than the
  // projector: an 8x8 cell holds ~3-4 camera pixels, and min_samples = 3 drops the sparser half),
  // median 0.16 / 0.13 px, 99th percentile 0.70 / 0.53 px, max 2.3 / 2.2 px: the worst are the
  // outermost cells, extrapolated from edges at least edge_margin camera pixels inside the lit rim.
  EXPECT_GT(fitted.coverage, 0.2);
  EXPECT_LE(fitted.median, 0.3);
  EXPECT_LE(fitted.p99, 1.0);
  EXPECT_LE(fitted.max, 3.0);
  // For the record: plain averaging of the block centres (fit_radius 0) is much noisier.
  CorrespondenceOptions plain;
  plain.fit_radius = 0;
  const Measured averaged = runScene(scene, camera, plain, pose);
  EXPECT_GT(averaged.median, fitted.median);
}

INSTANTIATE_TEST_SUITE_P(Projector, SimulatedCorrespondences, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return info.param ? std::string("WideAngle") : std::string("Pinhole");
                         });

TEST(FloorCorrespondences, BadInputIsRefused)
{
  const LensCalibration camera = simpleCamera(-0.1);
  GrayDecodeResult decoded;
  decoded.error = "boom";
  EXPECT_NE(floorCorrespondences(decoded, camera, lookingDown(), 1280, 800).error.find("boom"), std::string::npos);
  decoded = GrayDecodeResult();
  EXPECT_FALSE(floorCorrespondences(decoded, camera, lookingDown(), 1280, 800).error.empty());  // empty images
  decoded.projector = cv::Mat(480, 640, CV_32FC2, cv::Scalar(std::nan(""), std::nan("")));
  decoded.bits = cv::Mat::zeros(480, 640, CV_8UC2);
  Correspondences c = floorCorrespondences(decoded, camera, lookingDown(), 1280, 800);
  EXPECT_TRUE(c.error.empty()) << c.error;  // nothing decoded: no points, no error
  EXPECT_TRUE(c.points.empty());
  EXPECT_EQ(c.coverage, 0.0);
  LensCalibration other = camera;
  other.width = 1280;
  EXPECT_NE(floorCorrespondences(decoded, other, lookingDown(), 1280, 800).error.find("captures are 640x480"),
            std::string::npos);
  other = camera;
  other.K[2] = std::nan("");
  EXPECT_NE(floorCorrespondences(decoded, other, lookingDown(), 1280, 800).error.find("K is not finite"),
            std::string::npos);
  CorrespondenceOptions options;
  options.cell = 0;
  EXPECT_FALSE(floorCorrespondences(decoded, camera, lookingDown(), 1280, 800, options).error.empty());
  options = CorrespondenceOptions();
  options.plane_z = std::nan("");
  EXPECT_FALSE(floorCorrespondences(decoded, camera, lookingDown(), 1280, 800, options).error.empty());
  EXPECT_FALSE(floorCorrespondences(decoded, camera, lookingDown(), 0, 800).error.empty());
  decoded.bits = cv::Mat::zeros(480, 640, CV_8UC1);
  EXPECT_FALSE(floorCorrespondences(decoded, camera, lookingDown(), 1280, 800).error.empty());
}
}  // namespace
}  // namespace rviz_projector
