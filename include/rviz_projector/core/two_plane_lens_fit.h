// The projector's intrinsics fx, fy, cx, cy with its mount and k1, k2, from dense points on two
// planes (issue 24: the floor and a tilted checkerboard, board_view.h). On one plane a focal length
// trades against height and cy against pitch (dense_mount_solver.h); a second, tilted plane breaks
// that: it is the classical two-plane calibration rig, seen in one view.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/projector_mount.h"
#include "rviz_projector/core/rigid_transform.h"

namespace rviz_projector
{
struct TwoPlaneLensOptions
{
  /// Fit k1, k2 (p1 = p2 = k3 = 0) too; false: the distortion stays the start's.
  bool fit_distortion = true;
  /// Outliers as DenseSolveOptions: above max(outlier_px, outlier_median_factor x median error).
  double outlier_px = 2.0;
  double outlier_median_factor = 4.0;
  /// Fewer board points (inliers) than this are refused.
  int min_board_points = 100;
  /// A weak fit is refused: 1-sigma focal length above this fraction of it, or 1-sigma principal
  /// point above this fraction of the image's width (height).
  double max_focal_stddev = 0.01;
  double max_principal_stddev = 0.02;
};

struct TwoPlaneLensFit
{
  bool ok = false;
  std::string error;                ///< one sentence (ok == false)
  PinholeModel lens;                ///< fitted fx, fy, cx, cy (the prior's size)
  LensDistortion distortion;        ///< fitted plumb_bob (k1, k2, 0, 0, 0), or the start's
  RigidTransform parent_T_optical;
  ProjectorMount mount;
  /// 1-sigma of fx, fy, cx, cy (pixels) and k1, k2 (0 when not fitted): OpenCV's, from the RMS
  /// residual of the points fitted as if their pixel errors were independent (dense points' errors
  /// are correlated over a few cells, so the true uncertainty can be larger).
  std::array<double, 4> lens_stddev{};
  std::array<double, 2> k_stddev{};
  int floor_inliers = 0;
  int board_inliers = 0;
  int outliers = 0;
  double rms_px = 0.0;        ///< over all inliers, projector pixels
  double board_rms_px = 0.0;  ///< over the board's inliers
  /// Over the floor inliers: distance on the floor between each point and where its pixel's ray
  /// lands in the fitted model (millimetres).
  double floor_median_mm = 0.0;
  double floor_max_mm = 0.0;
  double floor_rms_mm = 0.0;
};

/**
 * Pose, fx, fy, cx, cy (and k1, k2) from floor points (one plane z = const) and board points (a
 * tilted plane), FloorPoint as the dense solver takes them.
 *  - Start: `prior` lens, `distortion` and `parent_T_optical` (the dense floor solution).
 *  - Fit: cv::calibrateCamera (on at most 1,500 floor and 1,000 board inliers, evenly spread: its
 *    time grows faster than linearly with the points) on the single view of the non-coplanar points with
 *    CALIB_USE_INTRINSIC_GUESS (OpenCV accepts a non-planar rig only with a guess), tangential and
 *    k3 fixed at zero (all coefficients fixed without fit_distortion); pixels shifted by one image
 *    size (the principal point of a projector lies outside its image, as in solveMount). Then the
 *    points off the fit by the outlier rule are left out and the fit redone, until the inliers stop
 *    changing (at most 5 rounds). The pose is refined in double precision (cv::solvePnPRefineLM).
 *  - Refused (ok false): fewer than min_board_points board inliers or 100 floor inliers; a fit that
 *    fails, is not a usable lens (solverLensProblem), puts the projector below the floor, folds
 *    (LensDistortion::foldCheck) or is weak (the stddev limits).
 */
TwoPlaneLensFit fitLensOnTwoPlanes(const PinholeModel& prior, const LensDistortion& distortion,
                                   const RigidTransform& parent_T_optical, const std::vector<FloorPoint>& floor,
                                   const std::vector<FloorPoint>& board,
                                   const TwoPlaneLensOptions& options = TwoPlaneLensOptions());
}  // namespace rviz_projector
