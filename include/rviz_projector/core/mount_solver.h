// Solving the projector's mount pose from crosshairs measured on the floor (issue 12).
//
// Input: the lens (intrinsics, fixed) and, for each crosshair, the projector pixel it was drawn at
// and where its centre was measured in the parent frame (metres; z = 0 is the floor for base_link).
// Output: the mount, residuals, outliers, the expected floor error and warnings, or an error.
// OpenCV calib3d does the pose maths (IPPE for coplanar points, RANSAC, Levenberg-Marquardt).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/projector_mount.h"
#include "rviz_projector/core/vec2.h"
#include "rviz_projector/core/vec3.h"

namespace rviz_projector
{
struct FloorPoint
{
  int id = 0;
  Vec2 pixel;   ///< where the projector drew the crosshair
  Vec3 world;   ///< where its centre was measured, parent frame, metres
};

struct PointResidual
{
  int id = 0;
  double px = 0.0;  ///< reprojection error, projector pixels
  double mm = 0.0;  ///< distance on the point's plane (z = world.z) between measured and predicted, mm
  bool outlier = false;
};

/// A point coordinate beyond this (metres) is refused: it is almost certainly millimetres.
constexpr double kMaxFloorPointCoordinate = 50.0;

struct MountSolverOptions
{
  /// Expected measurement error of a floor point (tape measure), metres, 1 sigma.
  double tape_error = 0.003;
  /// A point further than this from the solution (on the floor) is an outlier, metres.
  double outlier_distance = 0.03;
  /// Also fit fx, fy, cx, cy (needs points off the floor plane).
  bool fit_intrinsics = false;
  /// Also fit the radial distortion k1, k2 (plumb_bob, p1 = p2 = k3 = 0; see solveMount for what
  /// it needs). Not together with fit_intrinsics.
  bool fit_distortion = false;

  /// Options for points measured to `tape_error` (metres, 1 sigma): a point 10 tape errors, and at
  /// least 3 cm, from the solution is an outlier (3 mm -> 3 cm, 1 cm -> 10 cm).
  static MountSolverOptions forTapeError(double tape_error)
  {
    MountSolverOptions options;
    options.tape_error = tape_error;
    options.outlier_distance = tape_error * 10.0 > 0.03 ? tape_error * 10.0 : 0.03;
    return options;
  }
};

struct ExpectedError
{
  std::string where;  ///< e.g. "crosshair 1", "2 m ahead"
  Vec3 world;         ///< the floor point it refers to
  double mm = 0.0;    ///< 1-sigma radial floor error there, millimetres
};

struct MountSolution
{
  bool ok = false;
  std::string error;                  ///< why there is no solution (ok == false)
  std::vector<std::string> warnings;  ///< weak geometry etc.; the solution is still printed
  ProjectorMount mount;
  RigidTransform parent_T_optical;
  PinholeModel lens;                  ///< the lens used (fitted with fit_intrinsics)
  /// With fit_distortion: the fitted plumb_bob (k1, k2, 0, 0, 0); otherwise none (the solver
  /// treats the lens as an ideal pinhole).
  LensDistortion distortion;
  std::vector<PointResidual> residuals;  ///< one per input point, in input order
  std::vector<int> outliers;          ///< ids rejected
  double rms_px = 0.0;                ///< over the inliers
  double rms_mm = 0.0;
  /// Of (rx, ry, rz, tx, ty, tz): OpenCV's rotation vector and translation of the parent frame in
  /// the optical frame (what solvePnP returns; p_optical = R(r) p_parent + t), row-major.
  /// The measurement error is on the floor, the fit minimises pixels, so: the sandwich
  /// H^-1 (sum J_i^T S_i J_i) H^-1 with H = J^T J, J the reprojection Jacobian of the inliers
  /// (cv::projectPoints), S_i = sigma^2 A_i A_i^T the pixel covariance of point i (A_i = d(u, v) /
  /// d(x, y) on its plane), sigma^2 the a-posteriori variance of a coordinate, sum(|residual on the
  /// plane|^2) / (2N - 6), but never less than tape_error^2 (so exact data does not claim zero error).
  /// With fit_intrinsics the pose block of the joint (pose, fx, fy, cx, cy) covariance (2N - 10).
  std::array<double, 36> covariance{};
  /// 1-sigma radial floor error (sqrt of the trace of the propagated 2x2 covariance) at the input's
  /// extreme crosshairs (top-left, top-right, bottom-left, bottom-right pixel among the inliers) and
  /// at the floor point 2 m ahead of the mount along its yaw (parent x, y + 2 m (cos yaw, sin yaw),
  /// z = 0) when that is in the image (otherwise a warning says so).
  std::vector<ExpectedError> expected;
  /// With fit_intrinsics: 1-sigma of the fitted fx, fy, cx, cy (pixels), same sigma as covariance.
  std::array<double, 4> lens_stddev{};
  /// With fit_distortion: 1-sigma of the fitted k1, k2 (the (pose, k1, k2) covariance, 2N - 8).
  std::array<double, 2> distortion_stddev{};
};

/// Problems of the input alone ("" when fine): fewer than 4 points, NaN/Inf, duplicate ids,
/// pixels outside the lens's image, values that look like millimetres (|x|, |y| or |z| > 50),
/// collinear points (smallest / largest singular value of the centred pixels, or of the centred
/// world points' two main directions, below 0.02).
std::string floorPointsProblem(const PinholeModel& lens, const std::vector<FloorPoint>& points);

/// Problems of the lens for solving ("" when fine): no image, focal lengths not positive and
/// finite, Tx or Ty not zero (a projector has no stereo baseline).
std::string solverLensProblem(const PinholeModel& lens);

/**
 * The mount from the points.
 *  - Input checks: solverLensProblem, floorPointsProblem (errors, ok == false).
 *  - Pose: IPPE when all points lie within 1 mm of one plane z = const (any height), else SQPnP and
 *    EPnP; every candidate refined by Levenberg-Marquardt (cv::solvePnPRefineLM); the physically
 *    valid one (optical centre above the lowest point, every point in front of the lens) with the
 *    smallest reprojection error wins. Pixels are used as given: PinholeModel's convention is
 *    OpenCV's (integer = pixel centre). No distortion (the project does not honour D yet).
 *  - Outliers: while a point lies further than outlier_distance from the fit (residual mm), the
 *    pose is fitted without each inlier in turn; the fit with the smallest truncated cost (sum of
 *    min(residual, outlier_distance)^2 over the inliers, as MSAC) is kept and the points further
 *    than outlier_distance from it are rejected. Fewer than 4 points left (6 with fit_intrinsics)
 *    is an error. Deterministic (no random sampling).
 *  - fit_intrinsics: needs points off one plane (RMS distance from their best plane >= 5 mm, else
 *    the error explains why) and 6+ points; cv::calibrateCamera on the single view (the given lens
 *    as the start, distortion fixed at zero; pixels shifted by one image size so that a principal
 *    point outside the image, normal for projectors, is accepted) in every fit above; refused when
 *    the fitted lens is too uncertain (1-sigma focal length > 2% or principal point > 4% of the
 *    image size, from the covariance below with its 2N - 10 degrees of freedom).
 *  - fit_distortion: every fit above also fits k1, k2 (Levenberg-Marquardt over pose, k1, k2 from
 *    k1 = k2 = 0, Jacobian from cv::projectPoints). A floor cannot tell distortion from pose unless
 *    the points reach out towards the image corners, so it needs 8+ points (8+ inliers after the
 *    outlier search) and, near each of the image's 4 corners (within 25% of its width and height),
 *    an inlier; and it is refused when the fit is too uncertain: the 1-sigma radial displacement of
 *    the fitted k1, k2 at the image corner (g C g^T, g = f (r^3, r^5), r = lens.cornerRadius(), C
 *    their covariance, sigma as above with 2N - 8) above kMaxFloorDistortionStddevPx. With a 3 mm
 *    tape error 9 crosshairs (3x3) are refused this way; 25 (5x5) measured to 1 mm are enough.
 *    Refused too when the fitted map folds before the image corner (LensDistortion::foldCheck).
 *  - Errors after solving: a point behind the projector, the projector below the points.
 *  - Warnings (solution still given): fewer than 6 inliers, nearly collinear (singular value ratio
 *    < 0.15), all pixels within a box under 40% of the image's width and height, a point off by more
 *    than outlier_distance that no single rejection explains, 2 m ahead not in the image.
 */
MountSolution solveMount(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                         const MountSolverOptions& options = MountSolverOptions());

/// Largest 1-sigma radial displacement (projector pixels at the image corner) of k1, k2 fitted to
/// floor points (solveMount with fit_distortion): about 2 mm on the floor 2 m away with a PA503W.
constexpr double kMaxFloorDistortionStddevPx = 2.0;

/// Where the ray through `pixel` of a projector at `parent_T_optical` meets the plane z = plane_z
/// of the parent frame; false when it does not (parallel, or behind the lens).
bool pixelOnPlane(const PinholeModel& lens, const RigidTransform& parent_T_optical, const Vec2& pixel,
                  double plane_z, Vec3& out);
/// The same through a distorting lens: the pixel's ray is its undistorted direction
/// (LensDistortion::undistort of its normalised coordinates).
bool pixelOnPlane(const PinholeModel& lens, const LensDistortion& distortion, const RigidTransform& parent_T_optical,
                  const Vec2& pixel, double plane_z, Vec3& out);
}  // namespace rviz_projector
