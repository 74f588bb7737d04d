// calibrate_projector --camera (issue 24): the projector's mount and distortion from structured
// light seen by the robot's own camera.
//
//   1. PatternCapture shows white, black and OpenCV's Gray code patterns (core grayCodeFrames)
//      through the ProjectorCamera's Pattern topic and captures a camera frame of each;
//   2. solveFromCaptures (ROS-free): decodeGrayCode -> the projector pixel lighting each camera pixel;
//      floorCorrespondences -> camera rays (undistorted with the camera's D) met with the floor;
//      solveMountDense -> the mount and k1, k2 (fx, fy, cx, cy kept: a flat floor cannot pin them);
//   3. runCameraCalibration reports coverage, residuals, the expected floor error, and writes the
//      mount file and the calibration (D = k1 k2 0 0 0, P = K) only when everything held.
// Each refusal is one sentence and writes nothing.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rviz_projector/calibration/calibrate_projector_options.h"
#include "rviz_projector/core/dense_mount_solver.h"
#include "rviz_projector/core/gray_code.h"
#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/projector_mount.h"
#include "rviz_projector/core/rigid_transform.h"

namespace rviz_projector
{
/// Thresholds of the refusals (fractions), documented in doc/guide/calibration.md.
struct CameraCalibrationLimits
{
  double min_lit = 0.02;        ///< of the camera's pixels lit by the white frame
  double max_saturated = 0.2;   ///< of the lit pixels saturated in the white frame
  double min_decoded = 0.5;     ///< of the lit pixels decoded
  double min_coverage = 0.2;    ///< of the projector image's cells with a correspondence
};

struct CameraCalibrationInput
{
  PinholeModel lens;                    ///< the projector's pixels (K's pinhole: it draws through D)
  LensCalibration camera;               ///< the camera's CameraInfo (K, D)
  RigidTransform floor_T_camera;        ///< the camera's optical frame in the floor frame
  const ProjectorMount* prior = nullptr;  ///< the current mount in the floor frame, or none
  bool fit_distortion = true;
  CameraCalibrationLimits limits;
};

struct CameraCalibrationResult
{
  std::string error;        ///< the refusal ("" when solved)
  GrayDecodeResult decoded; ///< statistics of the decoding
  std::size_t correspondences = 0;
  double coverage = 0.0;    ///< of the projector image's cells
  DenseMountSolution solution;  ///< in the floor frame
};

/// Steps 2 of the file comment; `captures` in grayCodeFrames() order.
CameraCalibrationResult solveFromCaptures(const CameraCalibrationInput& input, const std::vector<cv::Mat>& captures);

/// The whole --camera mode (a ROS node: ros::init already called). Exit status as CalibrateExit.
int runCameraCalibration(const CalibrateOptions& options, std::ostream& out, std::ostream& err);
}  // namespace rviz_projector
