// Solving the projector's mount and its radial distortion k1, k2 from thousands of floor points
// (issue 24: structured light seen by the robot's camera gives, for each lit floor point, the
// projector pixel that lights it).
//
// The lens's fx, fy, cx, cy stay fixed (the prior calibration's): on a flat floor a change of
// focal length is indistinguishable from a change of height, and one of cy from one of pitch, so a
// floor cannot pin them. k1, k2 (plumb_bob, p1 = p2 = k3 = 0) can be fitted: they bend the image's
// straight lines, which no pose does.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/projector_mount.h"

namespace rviz_projector
{
struct DenseSolveOptions
{
  /// Fit k1, k2 (p1 = p2 = k3 = 0); false: the distortion stays `distortion`.
  bool fit_distortion = true;
  /// The prior's distortion: the start of k1, k2 (its other coefficients are dropped when fitting),
  /// the distortion used as it is when fit_distortion is false.
  LensDistortion distortion;
  /// Try the homography + IPPE start (see solveMountDense). false: start from the prior alone
  /// (then it must be given), e.g. when the caller trusts its prior.
  bool homography_start = true;
  /// Outliers: a point whose reprojection error is above max(outlier_px, outlier_median_factor x
  /// the median reprojection error of all points) is left out. For Gaussian pixel noise the
  /// median error is 1.18 sigma, so 4 x median is 4.7 sigma (1 good point in 60,000 lost), while a
  /// noisier set (a coarse camera) raises the threshold with its noise instead of losing its points.
  double outlier_px = 2.0;
  double outlier_median_factor = 4.0;
  /// Fewer points (inliers) than this are refused: this is the dense solver; use solveMount for
  /// a few measured points.
  int min_points = 100;
  /// The points (inliers) must fall in at least this fraction of the cells of a 10 x 10 grid over
  /// the projector's image (a quarter of the image, e.g. its lower half's middle).
  double min_coverage = 0.25;
  /// With fit_distortion: the inliers must reach out to this fraction of the image corner's
  /// normalised radius (PinholeModel::cornerRadius), or the distortion is not seen.
  double min_radius_fraction = 0.6;
  /// A weak solve is refused: 1-sigma of any rotation-vector component above this (degrees), of
  /// any translation component (tvec, the parent origin in the optical frame) above this (metres),
  /// or a 1-sigma radial displacement of the fitted k1, k2 at the image corner above this (pixels).
  /// The covariance is MountSolution's sandwich (the noise is on the floor, from the residuals).
  double max_rotation_stddev_deg = 0.05;
  double max_translation_stddev = 0.005;
  double max_distortion_stddev_px = 0.5;
};

struct DenseMountSolution
{
  bool ok = false;
  std::string error;                  ///< one sentence: why there is no solution (ok == false)
  std::vector<std::string> warnings;  ///< e.g. 2 m ahead not in the image; the solution stands
  ProjectorMount mount;
  RigidTransform parent_T_optical;
  /// plumb_bob (k1, k2, 0, 0, 0) fitted, or options.distortion when fit_distortion is false.
  LensDistortion distortion;
  int inliers = 0;
  int outliers = 0;
  /// Over the inliers: RMS reprojection error (projector pixels); median and largest distance on
  /// the points' plane between each point and where its pixel's ray lands (millimetres).
  double rms_px = 0.0;
  double median_mm = 0.0;
  double max_mm = 0.0;
  double rms_mm = 0.0;  ///< RMS of those distances (the mount file's rms_mm)
  /// 1-sigma floor error at the extreme points (image corners) and 2 m ahead (as MountSolution's),
  /// from the (pose, k1, k2) covariance.
  std::vector<ExpectedError> expected;
  std::array<double, 2> k_stddev{};  ///< 1-sigma of k1, k2 (0 when not fitted)
};

/**
 * The mount (and k1, k2) from dense floor points.
 *  - `lens`: the prior intrinsics (kept). `points`: FloorPoint{id, projector pixel, point on one
 *    plane z = const of the parent frame (the floor)}, typically 2,000 - 20,000; input checks as
 *    floorPointsProblem, and all z within 1 mm of each other.
 *  - Start: IPPE (cv::solvePnP) on the inliers of a RANSAC homography (cv::findHomography, 10 px)
 *    between the plane and the pixels' normalised coordinates undistorted by options.distortion;
 *    with a `prior` mount also the prior's pose; the start with the smaller median reprojection
 *    error wins (so a prior 3 deg / 5 cm off, or none, both work).
 *  - Fit: Levenberg-Marquardt over (rvec, tvec[, k1, k2]) minimising pixel reprojection errors
 *    (Jacobian from cv::projectPoints), on the points within 64, 32, 16, 8, 4 px in turn, then on
 *    the inliers of the outlier rule (DenseSolveOptions::outlier_px) until they stop changing.
 *  - Refused (ok false, one sentence): bad lens/points/options; fewer than min_points points or
 *    inliers; coverage below min_coverage; with fit_distortion, points not reaching
 *    min_radius_fraction of the corner radius; a fitted distortion that folds before the image
 *    corner (LensDistortion::foldCheck(lens.cornerRadius())); a weak solve (the stddev limits);
 *    the projector at or below the points' plane, or an inlier behind it.
 */
DenseMountSolution solveMountDense(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                                   const ProjectorMount* prior, const DenseSolveOptions& options = DenseSolveOptions());
}  // namespace rviz_projector
