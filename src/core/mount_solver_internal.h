// Internals of the mount solver shared by its source files (not installed, not an API).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/mount_solver.h"

namespace rviz_projector
{
namespace mount_solver_detail
{
/// OpenCV's pose: p_optical = R(rvec) p_parent + tvec.
struct Pose
{
  cv::Vec3d rvec;
  cv::Vec3d tvec;
};

RigidTransform parentTOptical(const Pose& pose);
/// The inverse: OpenCV's pose of an optical frame at `parent_T_optical`.
Pose poseOf(const RigidTransform& parent_T_optical);
/// The median (the upper one of an even count); HUGE_VAL for no values. The dense solver's and the
/// two-plane lens fit's residual statistics.
double median(std::vector<double> values);
/// A number as the solver's messages print it (shortest round-trip-ish form of an ostream).
std::string num(double v);
cv::Matx33d cameraMatrix(const PinholeModel& lens);
std::vector<cv::Point3d> objectPoints(const std::vector<FloorPoint>& points, const std::vector<int>& which);
std::vector<cv::Point2d> imagePoints(const std::vector<FloorPoint>& points, const std::vector<int>& which);

/// Smallest / largest singular value of the centred points (2 columns: pixels; for world points
/// the second / first of 3, i.e. how far from a line).
double pixelSpreadRatio(const std::vector<FloorPoint>& points, const std::vector<int>& which);
double worldSpreadRatio(const std::vector<FloorPoint>& points, const std::vector<int>& which);
/// All world z within 1 mm of each other.
bool coplanarZ(const std::vector<FloorPoint>& points, const std::vector<int>& which);

/// Weak-geometry warnings for the inliers.
std::vector<std::string> geometryWarnings(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                                          const std::vector<int>& inliers);

/// What is fitted besides the pose; selects the columns of cv::projectPoints' Jacobian.
enum class Extra
{
  None,        ///< the pose (6 parameters)
  Intrinsics,  ///< + fx, fy, cx, cy (10)
  Distortion,  ///< + k1, k2 (8)
};

/// Covariance of (rvec, tvec[, extra]) (see MountSolution::covariance), with `distortion` applied
/// to the pixels. sigma^2 (per floor coordinate) from the residuals on the plane, never below
/// tape_error^2. Writes the full matrix (6, 10 or 8 square); false when J^T J cannot be inverted.
bool poseCovariance(const PinholeModel& lens, const LensDistortion& distortion, const Pose& pose,
                    const std::vector<FloorPoint>& points, const std::vector<int>& inliers, double tape_error,
                    Extra extra, cv::Mat& covariance);
/// The expected floor errors (MountSolution::expected) from a covariance of (rvec, tvec) (6 x 6) or
/// of (rvec, tvec, k1, k2) (8 x 8; k1, k2 perturbed in `distortion`); warnings appended. `what`
/// names a point in ExpectedError::where ("crosshair", "point").
void expectedErrors(const PinholeModel& lens, const LensDistortion& distortion, const Pose& pose,
                    const cv::Mat& covariance, const std::vector<FloorPoint>& points,
                    const std::vector<int>& inliers, const std::string& what, std::vector<ExpectedError>& expected,
                    std::vector<std::string>& warnings);

/// OpenCV's coefficient vector of a distortion: 5 zeros for none (so k1, k2 can be fitted), else
/// its coefficients.
std::vector<double> coefficientsOf(const LensDistortion& distortion);
/// plumb_bob (k1, k2, 0, 0, 0) (none when both are zero).
LensDistortion radialDistortion(double k1, double k2);

/// Levenberg-Marquardt over the pose and, with fit_k, k1 and k2 (coefficients[0], [1]; the others
/// stay as given), minimising the squared pixel reprojection error of object -> image; Jacobian
/// from cv::projectPoints. `pose` and `coefficients` are the start and the result. False (inputs
/// unchanged) when the result is not finite or no step could be taken from a singular start.
bool refinePose(const PinholeModel& lens, const std::vector<cv::Point3d>& object,
                const std::vector<cv::Point2d>& image, bool fit_k, Pose& pose, std::vector<double>& coefficients,
                int max_iterations = 100);

/// Reprojection errors (pixels) of the points under the model; HUGE_VAL behind the lens.
std::vector<double> reprojectionErrors(const PinholeModel& lens, const std::vector<double>& coefficients,
                                       const Pose& pose, const std::vector<FloorPoint>& points,
                                       const std::vector<int>& which);
/// Where each pixel's ray meets its plane z (the points' world.z), through the distortion;
/// `hit[i]` false where it does not.
void pixelsOnPlanes(const PinholeModel& lens, const LensDistortion& distortion, const RigidTransform& parent_T_optical,
                    const std::vector<Vec2>& pixels, const std::vector<double>& plane_z, std::vector<Vec3>& out,
                    std::vector<bool>& hit);
/// pixelsOnPlanes for the points `which` (each pixel on its own point's plane z).
void pointsOnPlanes(const PinholeModel& lens, const LensDistortion& distortion, const RigidTransform& parent_T_optical,
                    const std::vector<FloorPoint>& points, const std::vector<int>& which, std::vector<Vec3>& out,
                    std::vector<bool>& hit);
/// 1-sigma displacement (pixels, along the radius) of a fitted k1, k2 at the image corner from
/// their 2 x 2 covariance: g C g^T with g = max(fx, fy) (r^3, r^5), r = lens.cornerRadius().
double distortionCornerStddevPx(const PinholeModel& lens, const cv::Matx22d& k_covariance);
}  // namespace mount_solver_detail
}  // namespace rviz_projector
