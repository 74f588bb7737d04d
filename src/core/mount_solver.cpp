// Mount solver: pose fitting with OpenCV calib3d and outlier rejection (see mount_solver.h).
#include "rviz_projector/core/mount_solver.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "mount_solver_internal.h"

namespace rviz_projector
{
using namespace mount_solver_detail;

namespace
{
/// Largest accepted 1-sigma of a fitted focal length (relative) and principal point (fraction of
/// the image's width / height) in the intrinsics mode.
constexpr double kMaxFocalStddev = 0.02;
constexpr double kMaxCentreStddev = 0.04;
/// RMS distance from their best-fitting plane (metres) below which the points are one plane for
/// the intrinsics mode.
constexpr double kPlanarRms = 0.005;
const cv::TermCriteria kRefine(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, DBL_EPSILON);

/// With fit_distortion: an inlier within this fraction of the image's width and height of each
/// image corner is needed.
constexpr double kCornerReach = 0.25;
constexpr std::size_t kMinDistortionPoints = 8;

struct Fit
{
  bool ok = false;
  Pose pose;
  PinholeModel lens;
  LensDistortion distortion;  ///< fitted k1, k2 (fit_distortion), else none
};

/// Depth of a world point in the optical frame.
double depthOf(const Pose& pose, const Vec3& w)
{
  cv::Matx33d r;
  cv::Rodrigues(pose.rvec, r);
  return (r * cv::Vec3d(w.x, w.y, w.z) + pose.tvec)[2];
}

/// Optical centre above the lowest point, every point in front of the lens.
bool physicallyValid(const Pose& pose, const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  double lowest = HUGE_VAL;
  for (int i : which)
  {
    const Vec3& w = points[static_cast<std::size_t>(i)].world;
    lowest = std::min(lowest, w.z);
    if (!(depthOf(pose, w) > 0.0))
    {
      return false;
    }
  }
  return parentTOptical(pose).translation().z > lowest;
}

double squaredReprojection(const PinholeModel& lens, const Pose& pose, const std::vector<cv::Point3d>& object,
                           const std::vector<cv::Point2d>& image)
{
  std::vector<cv::Point2d> projected;
  cv::projectPoints(object, pose.rvec, pose.tvec, cameraMatrix(lens), cv::noArray(), projected);
  double sum = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i)
  {
    const cv::Point2d d = image[i] - projected[i];
    sum += d.dot(d);
  }
  return sum;
}

/// Fixed lens: IPPE (coplanar) or SQPnP/EPnP candidates, each refined by LM; the valid one with the
/// smallest reprojection error.
Fit fitFixedLens(const PinholeModel& lens, const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  const std::vector<cv::Point3d> object = objectPoints(points, which);
  const std::vector<cv::Point2d> image = imagePoints(points, which);
  const cv::Mat k(cameraMatrix(lens));
  std::vector<cv::Mat> rvecs, tvecs;
  // Coplanar points: IPPE, and SQPnP as well (IPPE gave NaN poses for some exact 8-point subsets of
  // the 3x3 pattern, left by the outlier search; SQPnP solves planar sets too).
  const std::vector<int> methods = coplanarZ(points, which)
                                       ? std::vector<int>{cv::SOLVEPNP_IPPE, cv::SOLVEPNP_SQPNP}
                                       : std::vector<int>{cv::SOLVEPNP_SQPNP, cv::SOLVEPNP_EPNP};
  for (int method : methods)
  {
    std::vector<cv::Mat> r, t;
    try
    {
      cv::solvePnPGeneric(object, image, k, cv::noArray(), r, t, false, static_cast<cv::SolvePnPMethod>(method));
    }
    catch (const cv::Exception&)
    {
      continue;  // degenerate configuration for this method
    }
    rvecs.insert(rvecs.end(), r.begin(), r.end());
    tvecs.insert(tvecs.end(), t.begin(), t.end());
  }
  Fit best;
  double best_error = HUGE_VAL;
  for (std::size_t s = 0; s < rvecs.size(); ++s)
  {
    cv::Mat rvec, tvec;
    rvecs[s].convertTo(rvec, CV_64F);
    tvecs[s].convertTo(tvec, CV_64F);
    try
    {
      cv::solvePnPRefineLM(object, image, k, cv::noArray(), rvec, tvec, kRefine);
    }
    catch (const cv::Exception&)
    {
      continue;
    }
    const Pose pose{cv::Vec3d(rvec.ptr<double>()), cv::Vec3d(tvec.ptr<double>())};
    const double error = squaredReprojection(lens, pose, object, image);
    if (std::isfinite(error) && error < best_error && physicallyValid(pose, points, which))
    {
      best = {true, pose, lens, LensDistortion()};
      best_error = error;
    }
  }
  return best;
}

/// Lens and pose together: cv::calibrateCamera on the one view, distortion fixed at zero, started
/// from `lens`; then the pose refined in double precision. calibrateCamera insists on a principal
/// point inside the image, and a projector's lies below it (PA503W: cy = 817 of 800 rows): the
/// pixels are handed over shifted by one image size into an image three times as large (a pure
/// translation of the pixel frame, undone on the result), so the principal point may lie anywhere
/// within one image size around the image.
Fit fitWithLens(const PinholeModel& lens, const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  const double ox = lens.width(), oy = lens.height();
  std::vector<std::vector<cv::Point3f>> object(1);
  std::vector<std::vector<cv::Point2f>> image(1);
  for (int i : which)
  {
    const FloorPoint& p = points[static_cast<std::size_t>(i)];
    object[0].emplace_back(static_cast<float>(p.world.x), static_cast<float>(p.world.y), static_cast<float>(p.world.z));
    image[0].emplace_back(static_cast<float>(p.pixel.x + ox), static_cast<float>(p.pixel.y + oy));
  }
  if (!(std::fabs(lens.cx() - lens.width() / 2.0) < 1.5 * lens.width() &&
        std::fabs(lens.cy() - lens.height() / 2.0) < 1.5 * lens.height()))
  {
    return {};
  }
  cv::Mat k = (cv::Mat_<double>(3, 3) << lens.fx(), 0.0, lens.cx() + ox, 0.0, lens.fy(), lens.cy() + oy, 0.0, 0.0, 1.0);
  cv::Mat distortion = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  const int flags = cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_K1 | cv::CALIB_FIX_K2 | cv::CALIB_FIX_K3 |
                    cv::CALIB_FIX_K4 | cv::CALIB_FIX_K5 | cv::CALIB_FIX_K6 | cv::CALIB_ZERO_TANGENT_DIST;
  try
  {
    cv::calibrateCamera(object, image, cv::Size(3 * static_cast<int>(lens.width()), 3 * static_cast<int>(lens.height())),
                        k, distortion, rvecs, tvecs, flags, kRefine);
  }
  catch (const cv::Exception&)
  {
    return {};
  }
  const PinholeModel fitted(lens.width(), lens.height(), k.at<double>(0, 0), k.at<double>(1, 1),
                            k.at<double>(0, 2) - ox, k.at<double>(1, 2) - oy);
  if (!solverLensProblem(fitted).empty() || rvecs.size() != 1)
  {
    return {};
  }
  cv::Mat rvec, tvec;
  rvecs[0].convertTo(rvec, CV_64F);
  tvecs[0].convertTo(tvec, CV_64F);
  cv::solvePnPRefineLM(objectPoints(points, which), imagePoints(points, which), cv::Mat(cameraMatrix(fitted)),
                       cv::noArray(), rvec, tvec, kRefine);
  const Pose pose{cv::Vec3d(rvec.ptr<double>()), cv::Vec3d(tvec.ptr<double>())};
  if (!physicallyValid(pose, points, which))
  {
    return {};
  }
  return {true, pose, fitted, LensDistortion()};
}

/// The pinhole pose, then pose, k1, k2 refined together from k1 = k2 = 0.
Fit fitWithDistortion(const PinholeModel& lens, const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  Fit start = fitFixedLens(lens, points, which);
  if (!start.ok)
  {
    return {};
  }
  std::vector<double> coefficients(5, 0.0);
  if (!refinePose(lens, objectPoints(points, which), imagePoints(points, which), true, start.pose, coefficients) ||
      !physicallyValid(start.pose, points, which))
  {
    return {};
  }
  start.distortion = radialDistortion(coefficients[0], coefficients[1]);
  return start;
}

Fit fit(const PinholeModel& lens, const std::vector<FloorPoint>& points, const std::vector<int>& which,
        const MountSolverOptions& options)
{
  if (options.fit_intrinsics)
  {
    return fitWithLens(lens, points, which);
  }
  return options.fit_distortion ? fitWithDistortion(lens, points, which) : fitFixedLens(lens, points, which);
}

/// Which image corners have no inlier within kCornerReach of them ("" when all do).
std::string uncoveredCorners(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                             const std::vector<int>& inliers)
{
  const char* const names[4] = {"top left", "top right", "bottom left", "bottom right"};
  std::string missing;
  for (int corner = 0; corner < 4; ++corner)
  {
    const double cu = corner % 2 == 0 ? 0.0 : lens.width(), cv = corner < 2 ? 0.0 : lens.height();
    const bool covered = std::any_of(inliers.begin(), inliers.end(), [&](int i) {
      const Vec2& p = points[static_cast<std::size_t>(i)].pixel;
      return std::fabs(p.x - cu) <= kCornerReach * lens.width() && std::fabs(p.y - cv) <= kCornerReach * lens.height();
    });
    if (!covered)
    {
      missing += (missing.empty() ? "" : ", ") + std::string(names[corner]);
    }
  }
  return missing;
}

/// Distance on the point's plane between the measured point and where its crosshair's ray lands.
double residualMm(const Fit& f, const FloorPoint& p)
{
  Vec3 hit;
  if (!pixelOnPlane(f.lens, f.distortion, parentTOptical(f.pose), p.pixel, p.world.z, hit))
  {
    return HUGE_VAL;
  }
  return 1000.0 * std::hypot(hit.x - p.world.x, hit.y - p.world.y);
}

double residualPx(const Fit& f, const std::vector<FloorPoint>& points, int i)
{
  return reprojectionErrors(f.lens, coefficientsOf(f.distortion), f.pose, points, {i})[0];
}

MountSolution failure(const std::string& error)
{
  MountSolution s;
  s.error = error;
  return s;
}

const char* const kNoLensFit =
    "fitting intrinsics: cv::calibrateCamera found no lens and pose with the projector above the points and all "
    "of them in front of it: check the points, and start from a lens near the real one";
const char* const kNoValidPose =
    "no pose puts the projector above the points with all of them in front of it: check that each pixel "
    "belongs to its id and that x, y, z are in the parent frame";
}  // namespace

bool pixelOnPlane(const PinholeModel& lens, const RigidTransform& parent_T_optical, const Vec2& pixel, double plane_z,
                  Vec3& out)
{
  const Vec3 origin = parent_T_optical.apply(lens.centre());
  const Vec3 direction = parent_T_optical.rotate(lens.ray(pixel));
  if (!(std::fabs(direction.z) > 1e-12) || !isFinite(origin) || !isFinite(direction))
  {
    return false;
  }
  const double s = (plane_z - origin.z) / direction.z;
  if (!(s > 0.0) || !std::isfinite(s))
  {
    return false;
  }
  out = origin + direction * s;
  return true;
}

MountSolution solveMount(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                         const MountSolverOptions& options)
{
  if (const std::string problem = solverLensProblem(lens); !problem.empty())
  {
    return failure(problem);
  }
  if (const std::string problem = floorPointsProblem(lens, points); !problem.empty())
  {
    return failure(problem);
  }
  if (!(options.tape_error >= 0.0) || !(options.outlier_distance > 0.0) || !std::isfinite(options.tape_error) ||
      !std::isfinite(options.outlier_distance))
  {
    return failure("tape_error must be >= 0 and outlier_distance > 0 (metres)");
  }
  std::vector<int> inliers(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    inliers[i] = static_cast<int>(i);
  }
  const bool with_lens = options.fit_intrinsics;
  if (with_lens && options.fit_distortion)
  {
    return failure("fitting intrinsics and distortion together is not supported: fit the intrinsics first (points "
                   "off the floor), then k1, k2 with the fitted lens");
  }
  if (options.fit_distortion && points.size() < kMinDistortionPoints)
  {
    return failure("fitting k1, k2 needs at least " + std::to_string(kMinDistortionPoints) +
                   " points spread out to the image corners, got " + std::to_string(points.size()));
  }
  const std::size_t min_points = with_lens ? 6 : options.fit_distortion ? kMinDistortionPoints : 4;
  if (with_lens)
  {
    // RMS distance of the points from their best-fitting plane (any tilt): the smallest singular
    // value of the centred points / sqrt(N).
    cv::Mat w;
    const std::vector<cv::Point3d> object = objectPoints(points, inliers);  // cv::Mat only borrows it
    const cv::Mat rows = cv::Mat(object).reshape(1);
    cv::Mat mean;
    cv::reduce(rows, mean, 0, cv::REDUCE_AVG);
    cv::SVD::compute(rows - cv::repeat(mean, rows.rows, 1), w, cv::SVD::NO_UV);
    if (w.at<double>(2) / std::sqrt(static_cast<double>(rows.rows)) < kPlanarRms)
    {
      return failure("fitting intrinsics: floor points alone cannot tell focal length and cy apart from distance and "
                     "pitch: add 3+ points off the floor plane (z given), e.g. on a box");
    }
    if (points.size() < min_points)
    {
      return failure("fitting intrinsics needs at least 6 points, got " + std::to_string(points.size()));
    }
  }

  // Fit; while a point lies further than outlier_distance from the fit: fit without each inlier
  // in turn and keep the fit with the smallest truncated cost (sum over the inliers of
  // min(residual, outlier_distance)^2, as MSAC scores), then reject the points further than
  // outlier_distance from it. A fit without the bad point matches all the others closely, while a
  // fit that still holds it is pulled away from several (the largest leave-one-out residual is no
  // guide: a pulled fit extrapolates badly to the corner crosshairs, and a bad corner crosshair
  // pulls the fit towards itself).
  // A point with a wrong z (typed in cm, or a plane its crosshair's ray cannot reach) is such an
  // outlier too: its residual is infinite, and a fit that holds it may not be physically valid at
  // all (the point above the projector or behind it), so a failed fit of all points is also
  // answered by leaving out each point in turn.
  const char* const no_pose = with_lens ? kNoLensFit : kNoValidPose;
  Fit current = fit(lens, points, inliers, options);
  const double limit_mm = 1000.0 * options.outlier_distance;
  std::vector<int> outliers;
  std::vector<std::string> robust_warnings;
  while (true)
  {
    double worst = current.ok ? 0.0 : HUGE_VAL;
    int worst_id = -1;
    for (int i : inliers)
    {
      const double r = current.ok ? residualMm(current, points[static_cast<std::size_t>(i)]) : HUGE_VAL;
      if (r > worst || worst_id < 0)
      {
        worst = std::max(worst, r), worst_id = points[static_cast<std::size_t>(i)].id;
      }
    }
    if (current.ok && worst <= limit_mm)
    {
      break;
    }
    std::vector<int> best_agree;
    double best_cost = HUGE_VAL;
    for (int candidate : inliers)
    {
      std::vector<int> others;
      std::copy_if(inliers.begin(), inliers.end(), std::back_inserter(others), [&](int i) { return i != candidate; });
      if (others.size() < min_points)
      {
        break;
      }
      const Fit without = fit(lens, points, others, options);
      if (!without.ok)
      {
        continue;
      }
      std::vector<int> agree;
      double cost = 0.0;
      for (int i : inliers)
      {
        const double r = residualMm(without, points[static_cast<std::size_t>(i)]);
        cost += std::min(r, limit_mm) * std::min(r, limit_mm);
        if (r <= limit_mm)
        {
          agree.push_back(i);
        }
      }
      if (cost < best_cost)
      {
        best_agree = agree, best_cost = cost;
      }
    }
    if (!current.ok && best_agree.size() < min_points)
    {
      return failure(no_pose);
    }
    if (best_agree.size() < min_points)
    {
      return failure("the points do not agree with one mount (a residual of " +
                     (std::isfinite(worst) ? num(worst) + " mm" : std::string("infinity: a ray misses its point's plane")) +
                     " > outlier_distance " + num(limit_mm) + " mm) and no " + std::to_string(min_points) +
                     " or more of them agree once outliers are rejected: re-measure them");
    }
    if (best_agree.size() >= inliers.size())
    {
      if (!current.ok)
      {
        return failure(no_pose);
      }
      robust_warnings.push_back("point " + std::to_string(worst_id) + " is " + num(worst) +
                                " mm from the solution, more than outlier_distance, but leaving out no single point "
                                "explains it better: re-measure it");
      break;
    }
    for (int i : inliers)
    {
      if (std::find(best_agree.begin(), best_agree.end(), i) == best_agree.end())
      {
        outliers.push_back(i);
      }
    }
    inliers = best_agree;
    current = fit(lens, points, inliers, options);
    if (!current.ok)
    {
      return failure(no_pose);
    }
  }
  std::sort(outliers.begin(), outliers.end());

  MountSolution s;
  s.lens = current.lens;
  // The inliers decide; an outlier may be anywhere (behind the projector, above it, off its plane).
  for (int i : inliers)
  {
    const FloorPoint& p = points[static_cast<std::size_t>(i)];
    if (!(depthOf(current.pose, p.world) > 0.0))
    {
      return failure("point " + std::to_string(p.id) + " is behind the projector in the solution: check its x, y, z");
    }
  }
  s.parent_T_optical = parentTOptical(current.pose);
  double lowest = HUGE_VAL;
  for (int i : inliers)
  {
    lowest = std::min(lowest, points[static_cast<std::size_t>(i)].world.z);
  }
  if (!(s.parent_T_optical.translation().z > lowest))
  {
    return failure("the solution puts the projector below the points' plane: check the signs of x, y and the ids");
  }
  s.mount = mountOfOpticalPose(s.parent_T_optical);
  const ProjectorMount& m = s.mount;
  if (!std::isfinite(m.x) || !std::isfinite(m.y) || !std::isfinite(m.z) || !std::isfinite(m.roll) ||
      !std::isfinite(m.pitch) || !std::isfinite(m.yaw))
  {
    return failure("the solved mount is not finite");  // never printed as a solution, by any caller
  }
  double sum_px = 0.0, sum_mm = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    PointResidual r;
    r.id = points[i].id;
    r.px = residualPx(current, points, static_cast<int>(i));
    r.mm = residualMm(current, points[i]);
    r.outlier = std::find(outliers.begin(), outliers.end(), static_cast<int>(i)) != outliers.end();
    if (!r.outlier && (!std::isfinite(r.mm) || !std::isfinite(r.px)))
    {
      return failure("crosshair " + std::to_string(r.id) + "'s ray does not reach its point's plane in the solution");
    }
    // An outlier's ray may miss its plane (z wrong) or its point lie behind the lens: infinite.
    r.mm = std::isfinite(r.mm) ? r.mm : HUGE_VAL;
    r.px = std::isfinite(r.px) ? r.px : HUGE_VAL;
    if (r.outlier)
    {
      s.outliers.push_back(r.id);
    }
    else
    {
      sum_px += r.px * r.px, sum_mm += r.mm * r.mm;
    }
    s.residuals.push_back(r);
  }
  s.rms_px = std::sqrt(sum_px / static_cast<double>(inliers.size()));
  s.rms_mm = std::sqrt(sum_mm / static_cast<double>(inliers.size()));
  const Extra extra = with_lens ? Extra::Intrinsics : options.fit_distortion ? Extra::Distortion : Extra::None;
  cv::Mat covariance;
  if (!poseCovariance(current.lens, current.distortion, current.pose, points, inliers, options.tape_error, extra,
                      covariance))
  {
    return failure("the points do not determine the pose (singular Jacobian): spread them over the image");
  }
  for (int r = 0; r < 6; ++r)
  {
    for (int c = 0; c < 6; ++c)
    {
      s.covariance[static_cast<std::size_t>(6 * r + c)] = covariance.at<double>(r, c);
    }
  }
  if (with_lens)
  {
    for (int k = 0; k < 4; ++k)
    {
      s.lens_stddev[static_cast<std::size_t>(k)] = std::sqrt(std::max(0.0, covariance.at<double>(6 + k, 6 + k)));
    }
    const double sfx = s.lens_stddev[0] / s.lens.fx(), sfy = s.lens_stddev[1] / s.lens.fy();
    const double scx = s.lens_stddev[2] / s.lens.width(), scy = s.lens_stddev[3] / s.lens.height();
    if (!(std::max(sfx, sfy) <= kMaxFocalStddev && std::max(scx, scy) <= kMaxCentreStddev))
    {
      return failure("fitting intrinsics: the points cannot determine the lens well enough (1-sigma fx " +
                     num(s.lens_stddev[0]) + ", fy " + num(s.lens_stddev[1]) + ", cx " + num(s.lens_stddev[2]) +
                     ", cy " + num(s.lens_stddev[3]) + " px): add more points further off the floor plane "
                     "(z given), spread over the image");
    }
  }
  if (options.fit_distortion)
  {
    if (const std::string missing = uncoveredCorners(lens, points, inliers); !missing.empty())
    {
      return failure("fitting k1, k2 needs points near every image corner (within " + num(100 * kCornerReach) +
                     "% of the image's width and height of it); none near the " + missing +
                     " corner: use a pattern reaching the corners, e.g. --rows 5 --cols 5");
    }
    s.distortion = current.distortion;
    s.distortion_stddev = {std::sqrt(std::max(0.0, covariance.at<double>(6, 6))),
                           std::sqrt(std::max(0.0, covariance.at<double>(7, 7)))};
    const cv::Matx22d k_covariance = covariance(cv::Rect(6, 6, 2, 2));
    const double corner_px = distortionCornerStddevPx(lens, k_covariance);
    if (!(corner_px <= kMaxFloorDistortionStddevPx))
    {
      return failure("fitting k1, k2: " + std::to_string(inliers.size()) + " points measured to " +
                     num(1000.0 * options.tape_error) + " mm cannot pin the distortion (k1 " +
                     num(s.distortion_stddev[0]) + " and k2 " + num(s.distortion_stddev[1]) +
                     " 1-sigma: " + num(corner_px) + " px at the image corner, more than " +
                     num(kMaxFloorDistortionStddevPx) + "): measure more crosshairs (e.g. --rows 5 --cols 5) "
                     "more accurately, or leave out --fit-distortion");
    }
    const LensDistortion::Fold fold = current.distortion.foldCheck(lens.cornerRadius());
    if (fold.folds)
    {
      return failure("fitting k1, k2: the fitted " + LensDistortion::foldError(fold, lens.cornerRadius()));
    }
  }
  s.warnings = geometryWarnings(s.lens, points, inliers);
  s.warnings.insert(s.warnings.end(), robust_warnings.begin(), robust_warnings.end());
  expectedErrors(s.lens, current.distortion, current.pose,
                 options.fit_distortion ? covariance(cv::Rect(0, 0, 8, 8)) : covariance(cv::Rect(0, 0, 6, 6)), points,
                 inliers, "crosshair", s.expected, s.warnings);
  s.ok = true;
  return s;
}
}  // namespace rviz_projector
