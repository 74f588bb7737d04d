// Mount solver: input checks, weak-geometry warnings and conversions (see mount_solver.h).
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mount_solver_internal.h"
#include "rviz_projector/core/mount_solver.h"

namespace rviz_projector
{
namespace mount_solver_detail
{
namespace
{
/// Singular value ratio below which the points are collinear (error) / nearly so (warning).
constexpr double kCollinearError = 0.02;
constexpr double kCollinearWarning = 0.15;
/// Pixel bounding box (fraction of the image) below which the points crowd the centre.
constexpr double kCentredWarning = 0.4;
constexpr double kCoplanarTolerance = 0.001;

/// Singular values of the centred rows, descending.
std::vector<double> centredSingularValues(const cv::Mat& rows)
{
  cv::Mat mean;
  cv::reduce(rows, mean, 0, cv::REDUCE_AVG);
  cv::Mat centred = rows - cv::repeat(mean, rows.rows, 1);
  cv::Mat w;
  cv::SVD::compute(centred, w, cv::SVD::NO_UV);
  return std::vector<double>(w.begin<double>(), w.end<double>());
}

std::vector<int> allIndices(std::size_t n)
{
  std::vector<int> all(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    all[i] = static_cast<int>(i);
  }
  return all;
}
}  // namespace

double median(std::vector<double> values)
{
  if (values.empty())
  {
    return HUGE_VAL;
  }
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

std::string num(double v)
{
  std::ostringstream s;
  s << v;
  return s.str();
}


cv::Matx33d cameraMatrix(const PinholeModel& lens)
{
  return {lens.fx(), 0.0, lens.cx(), 0.0, lens.fy(), lens.cy(), 0.0, 0.0, 1.0};
}

RigidTransform parentTOptical(const Pose& pose)
{
  // parent_R_optical is the inverse rotation: axis-angle -rvec.
  const double angle = cv::norm(pose.rvec);
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
  if (angle > 0.0)
  {
    const double s = -std::sin(angle / 2) / angle;
    qx = pose.rvec[0] * s, qy = pose.rvec[1] * s, qz = pose.rvec[2] * s, qw = std::cos(angle / 2);
  }
  const RigidTransform rotation = RigidTransform::fromQuaternion(qx, qy, qz, qw, {});
  const Vec3 centre = rotation.rotate({-pose.tvec[0], -pose.tvec[1], -pose.tvec[2]});
  return RigidTransform::fromQuaternion(qx, qy, qz, qw, centre);
}

std::vector<cv::Point3d> objectPoints(const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  std::vector<cv::Point3d> out;
  for (int i : which)
  {
    const Vec3& w = points[static_cast<std::size_t>(i)].world;
    out.emplace_back(w.x, w.y, w.z);
  }
  return out;
}

std::vector<cv::Point2d> imagePoints(const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  std::vector<cv::Point2d> out;
  for (int i : which)
  {
    const Vec2& p = points[static_cast<std::size_t>(i)].pixel;
    out.emplace_back(p.x, p.y);
  }
  return out;
}

double pixelSpreadRatio(const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  const std::vector<cv::Point2d> pixels = imagePoints(points, which);  // cv::Mat only borrows it
  const std::vector<double> s = centredSingularValues(cv::Mat(pixels).reshape(1));
  return s.size() == 2 && s[0] > 0.0 ? s[1] / s[0] : 0.0;
}

double worldSpreadRatio(const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  const std::vector<cv::Point3d> world = objectPoints(points, which);  // cv::Mat only borrows it
  const std::vector<double> s = centredSingularValues(cv::Mat(world).reshape(1));
  return s.size() == 3 && s[0] > 0.0 ? s[1] / s[0] : 0.0;
}

bool coplanarZ(const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (int i : which)
  {
    lo = std::min(lo, points[static_cast<std::size_t>(i)].world.z);
    hi = std::max(hi, points[static_cast<std::size_t>(i)].world.z);
  }
  return hi - lo <= kCoplanarTolerance;
}

std::vector<std::string> geometryWarnings(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                                          const std::vector<int>& inliers)
{
  std::vector<std::string> warnings;
  if (inliers.size() < 6)
  {
    warnings.push_back("only " + std::to_string(inliers.size()) +
                       " points: with fewer than 6 a bad measurement is hard to detect and the pose is weakly "
                       "determined; measure 9 (the default 3x3 pattern) or more");
  }
  const double pixel_ratio = pixelSpreadRatio(points, inliers);
  const double world_ratio = worldSpreadRatio(points, inliers);
  if (std::min(pixel_ratio, world_ratio) < kCollinearWarning)
  {
    warnings.push_back("the points are nearly collinear (spread ratio " + num(std::min(pixel_ratio, world_ratio)) +
                       "): the tilt about their line is weakly determined; use crosshairs in at least 2 rows and "
                       "2 columns");
  }
  double u0 = HUGE_VAL, u1 = -HUGE_VAL, v0 = HUGE_VAL, v1 = -HUGE_VAL;
  for (int i : inliers)
  {
    const Vec2& p = points[static_cast<std::size_t>(i)].pixel;
    u0 = std::min(u0, p.x), u1 = std::max(u1, p.x), v0 = std::min(v0, p.y), v1 = std::max(v1, p.y);
  }
  if (u1 - u0 < kCentredWarning * lens.width() && v1 - v0 < kCentredWarning * lens.height())
  {
    warnings.push_back("all points are close to the image centre (they span " + num(u1 - u0) + " x " + num(v1 - v0) +
                       " pixels): the floor error grows quickly towards the image's edges; spread the "
                       "crosshairs over the image");
  }
  return warnings;
}
}  // namespace mount_solver_detail

std::string solverLensProblem(const PinholeModel& lens)
{
  if (lens.width() == 0 || lens.height() == 0)
  {
    return "the lens has no image size";
  }
  if (!(std::isfinite(lens.fx()) && std::isfinite(lens.fy()) && lens.fx() > 0.0 && lens.fy() > 0.0 &&
        std::isfinite(lens.cx()) && std::isfinite(lens.cy())))
  {
    return "the lens's fx, fy must be positive and fx, fy, cx, cy finite";
  }
  if (lens.tx() != 0.0 || lens.ty() != 0.0)
  {
    return "the lens's P has Tx = " + mount_solver_detail::num(lens.tx()) + ", Ty = " +
           mount_solver_detail::num(lens.ty()) + ": a projector has no stereo baseline, they must be 0";
  }
  return "";
}

std::string floorPointsProblem(const PinholeModel& lens, const std::vector<FloorPoint>& points)
{
  using mount_solver_detail::num;
  if (points.size() < 4)
  {
    return "need at least 4 points, got " + std::to_string(points.size());
  }
  std::set<int> ids;
  for (const FloorPoint& p : points)
  {
    const std::string which = "point " + std::to_string(p.id) + ": ";
    if (!isFinite(p.pixel) || !isFinite(p.world))
    {
      return which + "not a finite number (NaN or Inf)";
    }
    if (!ids.insert(p.id).second)
    {
      return "id " + std::to_string(p.id) + " appears more than once";
    }
    if (p.pixel.x < -0.5 || p.pixel.y < -0.5 || p.pixel.x > lens.width() - 0.5 || p.pixel.y > lens.height() - 0.5)
    {
      return which + "pixel (" + num(p.pixel.x) + ", " + num(p.pixel.y) + ") is outside the projector's image (" +
             std::to_string(lens.width()) + " x " + std::to_string(lens.height()) + ")";
    }
    const double k = kMaxFloorPointCoordinate;
    if (std::fabs(p.world.x) > k || std::fabs(p.world.y) > k || std::fabs(p.world.z) > k)
    {
      return which + "(" + num(p.world.x) + ", " + num(p.world.y) + ", " + num(p.world.z) +
             ") is more than 50 m away: values look like millimetres; points.yaml is in metres";
    }
  }
  const std::vector<int> all = mount_solver_detail::allIndices(points.size());
  const double pixel_ratio = mount_solver_detail::pixelSpreadRatio(points, all);
  const double world_ratio = mount_solver_detail::worldSpreadRatio(points, all);
  if (std::min(pixel_ratio, world_ratio) < mount_solver_detail::kCollinearError)
  {
    return std::string("the points are collinear (") + (pixel_ratio < world_ratio ? "pixels" : "floor positions") +
           ", spread ratio " + num(std::min(pixel_ratio, world_ratio)) +
           "): a line of points cannot fix the tilt about it; use crosshairs in at least 2 rows and 2 columns";
  }
  return "";
}
}  // namespace rviz_projector
