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

struct MountSolverOptions
{
  /// Expected measurement error of a floor point (tape measure), metres, 1 sigma.
  double tape_error = 0.003;
  /// A point further than this from the solution (on the floor) is an outlier, metres.
  double outlier_distance = 0.03;
  /// Also fit fx, fy, cx, cy (needs points off the floor plane).
  bool fit_intrinsics = false;
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
  std::vector<PointResidual> residuals;  ///< one per input point, in input order
  std::vector<int> outliers;          ///< ids rejected
  double rms_px = 0.0;                ///< over the inliers
  double rms_mm = 0.0;
  std::array<double, 36> covariance{};  ///< of (rx, ry, rz, tx, ty, tz) of the optical pose, row-major
  std::vector<ExpectedError> expected;  ///< at the pattern's corners and 2 m ahead of the mount
};

/// Problems of the input alone ("" when fine): fewer than 4 points, NaN/Inf, duplicate ids,
/// pixels outside the lens's image, values that look like millimetres, collinear points.
std::string floorPointsProblem(const PinholeModel& lens, const std::vector<FloorPoint>& points);

MountSolution solveMount(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                         const MountSolverOptions& options = MountSolverOptions());

/// Where the ray through `pixel` of a projector at `parent_T_optical` meets the plane z = plane_z
/// of the parent frame; false when it does not (parallel, or behind the lens).
bool pixelOnPlane(const PinholeModel& lens, const RigidTransform& parent_T_optical, const Vec2& pixel,
                  double plane_z, Vec3& out);
}  // namespace rviz_projector
