// calibrate_projector --camera from the captured frames on (issue 24): solveFromCaptures on frames
// of the test-only camera simulator (structured_light_sim.h: OpenCV's projectPoints/undistortPoints
// and its own mount convention), with the camera (640x480, 1 px blur, noise 2/255, 20 %
// ambient). The truth is the simulator's mount and lens; the fitted model's floor points are
// computed here with OpenCV from the solution's numbers and the simulator's convention.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>

#include "rviz_projector/core/structured_light_calibration.h"
#include "structured_light_sim.h"

namespace rviz_projector
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

/// Where projector pixel (u, v) lands on the floor z = 0 through `lens` at `pose`; false if not.
bool floorOf(const sim::Lens& lens, const sim::Pose& pose, double u, double v, cv::Point2d& out)
{
  std::vector<cv::Point2d> in{{u, v}}, ideal;
  cv::undistortPoints(in, ideal, cv::Mat(lens.K()), lens.distortion());
  const cv::Vec3d ray = pose.R * cv::Vec3d(ideal[0].x, ideal[0].y, 1.0);
  if (ray[2] >= -1e-9)
  {
    return false;
  }
  const double s = -pose.t[2] / ray[2];
  out = cv::Point2d(pose.t[0] + s * ray[0], pose.t[1] + s * ray[1]);
  return true;
}

struct CalibrationRun
{
  CameraCalibrationResult result;
  sim::Scene scene;
};

CalibrationRun calibrate(bool wide_angle, bool fit_distortion = true, double gain = sim::Scene().gain,
                         const LensDistortion& file_distortion = LensDistortion())
{
  CalibrationRun run;
  const sim::Scene scene = sim::demoScene(wide_angle);
  run.scene = scene;
  const sim::Camera camera = sim::demoCamera(wide_angle).withLight(scene.ambient, gain);
  const std::vector<PatternFrame> frames = grayCodeFrames(scene.projector.width, scene.projector.height);
  std::vector<cv::Mat> captures;
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    captures.push_back(camera.capture(frames[i].image, 1000 + i));
  }
  CameraCalibrationInput input;
  input.lens = PinholeModel(std::uint32_t(scene.projector.width), std::uint32_t(scene.projector.height),
                            scene.projector.fx, scene.projector.fy, scene.projector.cx, scene.projector.cy);
  input.camera = sim::calibrationOf(scene.camera);
  input.floor_T_camera = sim::transformOf(scene.camera_pose);
  // The prior: the mount the projector believes, 5 cm and 3 deg of pitch off the truth.
  const ProjectorMount prior{0.20, 0.0, 1.2, 0.0, 0.876 + 3.0 * kPi / 180.0, 0.0};
  input.prior = &prior;
  input.fit_distortion = fit_distortion;
  input.distortion = file_distortion;
  run.result = solveFromCaptures(input, captures);
  return run;
}

/// Floor errors (mm) of the fitted model against the truth over a 17 x 11 grid of projector pixels.
std::vector<double> floorErrors(const CalibrationRun& run)
{
  const DenseMountSolution& s = run.result.solution;
  sim::Lens fitted = run.scene.projector;
  fitted.D = s.distortion.coefficients();
  const sim::Pose fitted_pose = sim::mountPose(s.mount.x, s.mount.y, s.mount.z, s.mount.roll, s.mount.pitch, s.mount.yaw);
  std::vector<double> errors;
  for (int i = 0; i <= 16; ++i)
  {
    for (int j = 0; j <= 10; ++j)
    {
      const double u = i * (fitted.width - 1) / 16.0, v = j * (fitted.height - 1) / 10.0;
      cv::Point2d truth, got;
      if (!floorOf(run.scene.projector, run.scene.projector_pose, u, v, truth))
      {
        continue;
      }
      errors.push_back(floorOf(fitted, fitted_pose, u, v, got) ? 1000.0 * cv::norm(truth - got) : HUGE_VAL);
    }
  }
  std::sort(errors.begin(), errors.end());
  return errors;
}

void expectAccurate(const CalibrationRun& run, const char* what)
{
  const CameraCalibrationResult& r = run.result;
  ASSERT_TRUE(r.error.empty()) << what << ": " << r.error;
  const ProjectorMount& m = r.solution.mount;
  // The truth: demoScene's projector, 0.15 m ahead, 1.2 m up, pitched 0.876 rad.
  const double position_mm = 1000.0 * std::sqrt((m.x - 0.15) * (m.x - 0.15) + m.y * m.y + (m.z - 1.2) * (m.z - 1.2));
  const double roll = std::abs(m.roll) * 180.0 / kPi, pitch = std::abs(m.pitch - 0.876) * 180.0 / kPi,
               yaw = std::abs(m.yaw) * 180.0 / kPi;
  const std::vector<double> errors = floorErrors(run);
  const double median = errors[errors.size() / 2], worst = errors.back();
  const std::vector<double>& d = r.solution.distortion.coefficients();
  std::printf("  %s: mount %.2f mm, roll %.4f pitch %.4f yaw %.4f deg; k1 %.4f k2 %.4f; floor median %.2f max "
              "%.2f mm; coverage %.2f, %zu correspondences, %d inliers\n",
              what, position_mm, roll, pitch, yaw, d.empty() ? 0.0 : d[0], d.size() > 1 ? d[1] : 0.0, median, worst,
              r.coverage, r.correspondences, r.solution.inliers);
  EXPECT_LE(position_mm, 2.0) << what;
  EXPECT_LE(roll, 0.05) << what;
  EXPECT_LE(pitch, 0.05) << what;
  EXPECT_LE(yaw, 0.05) << what;
  EXPECT_LE(median, 1.0) << what;
  EXPECT_LE(worst, 3.0) << what;
}
}  // namespace

TEST(StructuredLightCalibration, RecoversTheMountOfAPinholeProjectorFromAWrongPrior)
{
  expectAccurate(calibrate(false), "pinhole");
}

TEST(StructuredLightCalibration, RecoversTheMountAndTheDistortionOfAWideAngleLens)
{
  const CalibrationRun run = calibrate(true);
  expectAccurate(run, "wide angle");
  const std::vector<double>& d = run.result.solution.distortion.coefficients();
  ASSERT_GE(d.size(), 2u);
  EXPECT_NEAR(d[0], -0.2, 0.01);
  EXPECT_NEAR(d[1], 0.05, 0.02);
}

TEST(StructuredLightCalibration, IgnoringTheWideAngleLensLeavesCentimetres)
{
  // The same captures with the distortion kept at zero (--keep-distortion on a file without D):
  // the 8 / 54 mm. Shows that the fit is what brings the floor error down.
  const CalibrationRun run = calibrate(true, false);
  if (!run.result.error.empty())
  {
    SUCCEED() << "refused: " << run.result.error;  // a refusal is fine too: never a wrong answer
    return;
  }
  const std::vector<double> errors = floorErrors(run);
  std::printf("  D kept at zero: floor median %.1f max %.1f mm\n", errors[errors.size() / 2], errors.back());
  EXPECT_GT(errors.back(), 10.0);
}

TEST(StructuredLightCalibration, AKnownDistortionIsKeptAndUsed)
{
  // --keep-distortion with a calibration file that has the true D: the mount is solved through it.
  const LensDistortion truth(LensDistortion::Model::PlumbBob, {-0.2, 0.05, 0.0, 0.0, 0.0});
  const CalibrationRun run = calibrate(true, false, sim::Scene().gain, truth);
  expectAccurate(run, "wide angle, D kept");
  EXPECT_EQ(run.result.solution.distortion.coefficients(), truth.coefficients());
}

TEST(StructuredLightCalibration, ACameraSeeingNothingLitIsRefused)
{
  const CalibrationRun run = calibrate(false, true, 0.0);  // the projector's light never reaches the camera
  EXPECT_NE(run.result.error.find("sees too little of the projection"), std::string::npos) << run.result.error;
}

TEST(StructuredLightCalibration, SaturatingPatternsAreRefused)
{
  const CalibrationRun run = calibrate(false, true, 3.0);  // white far beyond the camera's range
  EXPECT_NE(run.result.error.find("saturate"), std::string::npos) << run.result.error;
}

TEST(StructuredLightCalibration, FramesOfTheWrongPatternCannotBeDecodedAndAreRefused)
{
  // Every pattern frame captured while the white frame was still on (captured before its pattern
  // was on screen): white and black are right, no bit has contrast.
  const sim::Scene scene = sim::demoScene(false);
  const sim::Camera& camera = sim::demoCamera(false);
  const std::vector<PatternFrame> frames = grayCodeFrames(scene.projector.width, scene.projector.height);
  std::vector<cv::Mat> captures;
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    captures.push_back(camera.capture(frames[i < 2 ? i : 0].image, 2000 + i));
  }
  CameraCalibrationInput input;
  input.lens = PinholeModel(1280, 800, scene.projector.fx, scene.projector.fy, scene.projector.cx, scene.projector.cy);
  input.camera = sim::calibrationOf(scene.camera);
  input.floor_T_camera = sim::transformOf(scene.camera_pose);
  const CameraCalibrationResult result = solveFromCaptures(input, captures);
  EXPECT_NE(result.error.find("cannot be decoded"), std::string::npos) << result.error;
}

TEST(StructuredLightCalibration, WrongCaptureCountIsAnError)
{
  CameraCalibrationInput input;
  input.lens = PinholeModel(1280, 800, 1900, 1900, 640, 750);
  const CameraCalibrationResult result = solveFromCaptures(input, std::vector<cv::Mat>(3, cv::Mat(480, 640, CV_8UC1)));
  EXPECT_NE(result.error.find("cannot be decoded"), std::string::npos) << result.error;
}
}  // namespace rviz_projector
