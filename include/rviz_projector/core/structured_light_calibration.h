// Structured-light calibration of a projector by a camera that sees the floor (issue 24), from the
// captured frames on: ROS-free, so that it is tested with simulated captures.
//
//   decodeGrayCode       -> the projector pixel lighting each camera pixel (gray_code.h)
//   floorCorrespondences -> camera rays (undistorted with the camera's D) met with the floor z = 0
//                           (camera_floor.h)
//   solveMountDense      -> the mount and k1, k2; fx, fy, cx, cy kept (a flat floor cannot pin them)
//                           (dense_mount_solver.h)
// with a refusal, one sentence, at the first step that cannot give a sound answer.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

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
  /// The calibration file's distortion: kept as it is without fit_distortion, the start of k1, k2
  /// with it.
  LensDistortion distortion;
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

}  // namespace rviz_projector
