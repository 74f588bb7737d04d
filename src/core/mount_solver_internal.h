// Internals of the mount solver shared by its source files (not installed, not an API).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

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

/// Covariance of the pose (see MountSolution::covariance) and, with fit_intrinsics, lens_stddev.
/// False when J^T J cannot be inverted.
bool poseCovariance(const PinholeModel& lens, const Pose& pose, const std::vector<FloorPoint>& points,
                    const std::vector<int>& inliers, double tape_error, bool with_intrinsics, MountSolution& out);
/// The expected floor errors (MountSolution::expected) from out.covariance; warnings to out too.
void expectedErrors(const PinholeModel& lens, const Pose& pose, const std::vector<FloorPoint>& points,
                    const std::vector<int>& inliers, MountSolution& out);
}  // namespace mount_solver_detail
}  // namespace rviz_projector
