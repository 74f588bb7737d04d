// Structured-light calibration of a projector by a camera that sees the floor (issue 24), from the
// captured frames on: ROS-free, so that it is tested with simulated captures.
//
//   decodeGrayCode       -> the projector pixel lighting each camera pixel (gray_code.h)
//   floorCorrespondences -> camera rays (undistorted with the camera's D) met with the floor z = 0
//                           (camera_floor.h)
//   solveMountDense      -> the mount and k1, k2; fx, fy, cx, cy kept (a flat floor cannot pin them)
//                           (dense_mount_solver.h)
// and with a board (calibrate_projector --board):
//   findBoard            -> a checkerboard propped up tilted on the floor, found in the white frame:
//                           its plane and the camera pixels on it / near it (board_view.h)
//   floorCorrespondences -> twice: the pixels on the board met with its plane, those away from it
//                           with the floor
//   fitLensOnTwoPlanes   -> fx, fy, cx, cy with the mount and k1, k2 (two_plane_lens_fit.h), from
//                           the dense floor solution
// with a refusal, one sentence, at the first step that cannot give a sound answer.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rviz_projector/core/board_view.h"
#include "rviz_projector/core/dense_mount_solver.h"
#include "rviz_projector/core/gray_code.h"
#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/projector_mount.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/core/two_plane_lens_fit.h"

namespace rviz_projector
{
/// Thresholds of the refusals (fractions), documented in doc/guide/calibration.md.
struct CameraCalibrationLimits
{
  double min_lit = 0.02;        ///< of the camera's pixels lit by the white frame
  double max_saturated = 0.2;   ///< of the lit pixels saturated in the white frame
  double min_decoded = 0.5;     ///< of the lit pixels decoded
  double min_coverage = 0.2;    ///< of the projector image's cells with a correspondence
  int min_board_points = 100;   ///< correspondences on the board (projector cells of 8 x 8 pixels)
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
  /// Set: a checkerboard tilted on the floor in the camera's view; fx, fy, cx, cy are fitted too.
  std::optional<BoardSpec> board;
  CameraCalibrationLimits limits;
};

struct CameraCalibrationResult
{
  std::string error;        ///< the refusal ("" when solved)
  GrayDecodeResult decoded; ///< statistics of the decoding
  std::size_t correspondences = 0;
  double coverage = 0.0;    ///< of the projector image's cells
  DenseMountSolution solution;  ///< in the floor frame, the prior's fx, fy, cx, cy
  /// With a board: where it was found, its correspondences, and the fit of the lens (which then
  /// replaces `solution`'s mount and distortion).
  BoardView board;
  std::size_t board_correspondences = 0;
  bool lens_fitted = false;
  TwoPlaneLensFit lens_fit;
};

/// The steps of the file comment; `captures` in grayCodeFrames() order.
CameraCalibrationResult solveFromCaptures(const CameraCalibrationInput& input, const std::vector<cv::Mat>& captures);

}  // namespace rviz_projector
