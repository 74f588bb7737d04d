// Dense mount solver: pose and k1, k2 from thousands of floor points (see dense_mount_solver.h).
#include "rviz_projector/core/dense_mount_solver.h"

#include <algorithm>
#include <cmath>
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
constexpr int kCoverageCells = 10;
/// The RANSAC homography's threshold (pixels) and the largest number of its inliers given to IPPE.
constexpr double kHomographyPx = 10.0;
constexpr std::size_t kStartSample = 2000;
/// The thresholds (pixels) of the fit's first rounds, from the start's error down to the noise.
constexpr double kSchedule[] = {64.0, 32.0, 16.0, 8.0, 4.0};
constexpr int kFinalRounds = 6;

DenseMountSolution failure(const std::string& error)
{
  DenseMountSolution s;
  s.error = error;
  return s;
}

/// Fraction of the 10 x 10 cells of the image holding at least one of the points.
double coverage(const PinholeModel& lens, const std::vector<FloorPoint>& points, const std::vector<int>& which)
{
  std::vector<bool> cell(kCoverageCells * kCoverageCells, false);
  for (int i : which)
  {
    const Vec2& p = points[static_cast<std::size_t>(i)].pixel;
    const int cu = std::clamp(static_cast<int>((p.x + 0.5) / lens.width() * kCoverageCells), 0, kCoverageCells - 1);
    const int cv = std::clamp(static_cast<int>((p.y + 0.5) / lens.height() * kCoverageCells), 0, kCoverageCells - 1);
    cell[static_cast<std::size_t>(cv * kCoverageCells + cu)] = true;
  }
  return static_cast<double>(std::count(cell.begin(), cell.end(), true)) / static_cast<double>(cell.size());
}

std::vector<int> within(const std::vector<double>& errors, double threshold)
{
  std::vector<int> out;
  for (std::size_t i = 0; i < errors.size(); ++i)
  {
    if (errors[i] <= threshold)
    {
      out.push_back(static_cast<int>(i));
    }
  }
  return out;
}

/// The homography + IPPE start (see solveMountDense); false when there is none.
bool homographyStart(const PinholeModel& lens, const LensDistortion& distortion, const std::vector<FloorPoint>& points,
                     Pose& out)
{
  std::vector<Vec2> normalised;
  normalised.reserve(points.size());
  for (const FloorPoint& p : points)
  {
    const Vec3 ray = lens.ray(p.pixel);
    normalised.push_back({ray.x, ray.y});
  }
  const std::vector<Vec2> ideal = distortion.undistort(normalised);
  std::vector<cv::Point2d> plane, image;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    plane.emplace_back(points[i].world.x, points[i].world.y);
    image.emplace_back(ideal[i].x, ideal[i].y);
  }
  std::vector<unsigned char> mask;
  cv::Mat h;
  try
  {
    h = cv::findHomography(plane, image, cv::RANSAC, kHomographyPx / std::max(lens.fx(), lens.fy()), mask, 2000, 0.995);
  }
  catch (const cv::Exception&)
  {
    return false;
  }
  if (h.empty())
  {
    return false;
  }
  std::vector<int> inliers;
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    if (mask[i] != 0)
    {
      inliers.push_back(static_cast<int>(i));
    }
  }
  if (inliers.size() < 4)
  {
    return false;
  }
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> sample;
  const std::size_t step = std::max<std::size_t>(1, inliers.size() / kStartSample);
  for (std::size_t k = 0; k < inliers.size(); k += step)
  {
    const FloorPoint& p = points[static_cast<std::size_t>(inliers[k])];
    object.emplace_back(p.world.x, p.world.y, p.world.z);
    sample.push_back(image[static_cast<std::size_t>(inliers[k])]);
  }
  std::vector<cv::Mat> rvecs, tvecs;
  try
  {
    cv::solvePnPGeneric(object, sample, cv::Matx33d::eye(), cv::noArray(), rvecs, tvecs, false, cv::SOLVEPNP_IPPE);
  }
  catch (const cv::Exception&)
  {
    return false;
  }
  // Of IPPE's two solutions, the one with the projector above the plane and the points in front.
  for (std::size_t s = 0; s < rvecs.size(); ++s)
  {
    cv::Mat r, t;
    rvecs[s].convertTo(r, CV_64F);
    tvecs[s].convertTo(t, CV_64F);
    const Pose pose{cv::Vec3d(r.ptr<double>()), cv::Vec3d(t.ptr<double>())};
    cv::Matx33d rotation;
    cv::Rodrigues(pose.rvec, rotation);
    const bool in_front = std::all_of(object.begin(), object.end(), [&](const cv::Point3d& o) {
      return (rotation * cv::Vec3d(o.x, o.y, o.z) + pose.tvec)[2] > 0.0;
    });
    if (in_front && parentTOptical(pose).translation().z > object.front().z)
    {
      out = pose;
      return true;
    }
  }
  return false;
}

std::string checkOptions(const DenseSolveOptions& o)
{
  const double values[] = {o.outlier_px,   o.outlier_median_factor,  o.min_coverage,          o.min_radius_fraction,
                           o.max_rotation_stddev_deg, o.max_translation_stddev, o.max_distortion_stddev_px};
  if (!std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v) && v >= 0.0; }) ||
      !(o.outlier_px > 0.0) || o.min_points < 4)
  {
    return "the dense solver's options must be finite and >= 0, outlier_px > 0 and min_points >= 4";
  }
  if (!o.distortion.none() && std::any_of(o.distortion.coefficients().begin(), o.distortion.coefficients().end(),
                                          [](double v) { return !std::isfinite(v); }))
  {
    return "the prior distortion is not finite";
  }
  return "";
}
}  // namespace

DenseMountSolution solveMountDense(const PinholeModel& lens, const std::vector<FloorPoint>& points,
                                   const ProjectorMount* prior, const DenseSolveOptions& options)
{
  if (const std::string problem = solverLensProblem(lens); !problem.empty())
  {
    return failure(problem);
  }
  if (const std::string problem = checkOptions(options); !problem.empty())
  {
    return failure(problem);
  }
  const std::size_t min_points = static_cast<std::size_t>(options.min_points);
  if (points.size() < min_points)
  {
    return failure("need at least " + std::to_string(min_points) + " points for the dense solve, got " +
                   std::to_string(points.size()) + " (a few measured points: use solveMount)");
  }
  if (const std::string problem = floorPointsProblem(lens, points); !problem.empty())
  {
    return failure(problem);
  }
  std::vector<int> all(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    all[i] = static_cast<int>(i);
  }
  if (!coplanarZ(points, all))
  {
    return failure("the dense solver takes points on one plane z = const (the floor): their z differ by more than "
                   "1 mm");
  }
  const double all_coverage = coverage(lens, points, all);
  if (all_coverage < options.min_coverage)
  {
    return failure("the points cover " + num(std::round(100 * all_coverage)) + "% of the projector's image, at least " +
                   num(100 * options.min_coverage) + "% is needed (cells of a 10 x 10 grid holding a point)");
  }
  if (prior != nullptr && !(std::isfinite(prior->x) && std::isfinite(prior->y) && std::isfinite(prior->z) &&
                            std::isfinite(prior->roll) && std::isfinite(prior->pitch) && std::isfinite(prior->yaw)))
  {
    return failure("the prior mount is not finite");
  }

  // The start: homography + IPPE, and the prior; the smaller median reprojection error wins.
  const bool fit_k = options.fit_distortion;
  std::vector<double> coefficients = coefficientsOf(options.distortion);
  if (fit_k)
  {
    coefficients = {coefficients[0], coefficients[1], 0.0, 0.0, 0.0};
  }
  std::vector<Pose> starts;
  Pose start;
  if (prior == nullptr && !options.homography_start)
  {
    return failure("homography_start is off and no prior mount was given: nothing to start from");
  }
  if (options.homography_start && homographyStart(lens, options.distortion, points, start))
  {
    starts.push_back(start);
  }
  if (prior != nullptr)
  {
    starts.push_back(poseOf(opticalPoseOfMount(*prior)));
  }
  double best_median = HUGE_VAL;
  Pose pose;
  for (const Pose& candidate : starts)
  {
    const double m = median(reprojectionErrors(lens, coefficients, candidate, points, all));
    if (m < best_median)
    {
      best_median = m, pose = candidate;
    }
  }
  if (!std::isfinite(best_median))
  {
    return failure(std::string("no start pose: the points do not look like one plane seen by the projector (check "
                               "the pixels against the floor points), ") +
                   (prior == nullptr ? "and no prior mount was given"
                                     : "and the prior mount puts them behind the projector or off its image"));
  }

  // The fit: shrinking thresholds, then the outlier rule until the inliers stop changing.
  std::vector<int> inliers;
  const auto fitOn = [&](const std::vector<int>& which) {
    return which.size() >= min_points &&
           refinePose(lens, objectPoints(points, which), imagePoints(points, which), fit_k, pose, coefficients);
  };
  for (double threshold : kSchedule)
  {
    std::vector<int> next = within(reprojectionErrors(lens, coefficients, pose, points, all), threshold);
    if (next.size() >= min_points)
    {
      inliers = next;
      fitOn(inliers);
    }
  }
  double threshold = 0.0;
  for (int round = 0; round < kFinalRounds; ++round)
  {
    const std::vector<double> errors = reprojectionErrors(lens, coefficients, pose, points, all);
    threshold = std::max(options.outlier_px, options.outlier_median_factor * median(errors));
    std::vector<int> next = within(errors, threshold);
    if (next.size() < min_points)
    {
      return failure("only " + std::to_string(next.size()) + " of " + std::to_string(points.size()) +
                     " points agree with one mount within " + num(threshold) + " px, at least " +
                     std::to_string(min_points) + " are needed: check the correspondences");
    }
    if (next == inliers)
    {
      break;
    }
    inliers = next;
    if (!fitOn(inliers))
    {
      return failure("the fit did not converge to a finite mount: check the correspondences");
    }
  }

  DenseMountSolution s;
  s.distortion = fit_k ? radialDistortion(coefficients[0], coefficients[1]) : options.distortion;
  s.parent_T_optical = parentTOptical(pose);
  s.mount = mountOfOpticalPose(s.parent_T_optical);
  s.inliers = static_cast<int>(inliers.size());
  s.outliers = static_cast<int>(points.size() - inliers.size());

  // Physical checks.
  const double plane_z = points.front().world.z;
  if (!(s.parent_T_optical.translation().z > plane_z))
  {
    return failure("the solution puts the projector at or below the points' plane: check the signs of x, y");
  }
  const std::vector<double> errors = reprojectionErrors(lens, coefficients, pose, points, inliers);
  if (std::any_of(errors.begin(), errors.end(), [](double e) { return !std::isfinite(e); }))
  {
    return failure("the solution puts points behind the projector: check the correspondences");
  }
  const LensDistortion::Fold fold = s.distortion.foldCheck(lens.cornerRadius());
  if (fold.folds)
  {
    return failure("the fitted " + LensDistortion::foldError(fold, lens.cornerRadius()));
  }
  const double inlier_coverage = coverage(lens, points, inliers);
  if (inlier_coverage < options.min_coverage)
  {
    return failure("the points that agree with the mount cover " + num(std::round(100 * inlier_coverage)) +
                   "% of the projector's image, at least " + num(100 * options.min_coverage) + "% is needed");
  }
  if (fit_k)
  {
    double reach = 0.0;
    for (int i : inliers)
    {
      const Vec3 ray = lens.ray(points[static_cast<std::size_t>(i)].pixel);
      reach = std::max(reach, std::hypot(ray.x, ray.y));
    }
    if (reach < options.min_radius_fraction * lens.cornerRadius())
    {
      return failure("fitting k1, k2 needs points out to " + num(100 * options.min_radius_fraction) +
                     "% of the image corner's radius from the principal point; they reach " +
                     num(std::round(100 * reach / lens.cornerRadius())) + "%: light and see more of the image's "
                     "edges, or do not fit the distortion");
    }
  }

  // Residuals.
  double sum_px = 0.0;
  for (double e : errors)
  {
    sum_px += e * e;
  }
  s.rms_px = std::sqrt(sum_px / static_cast<double>(errors.size()));
  std::vector<Vec3> hits;
  std::vector<bool> hit;
  pointsOnPlanes(lens, s.distortion, s.parent_T_optical, points, inliers, hits, hit);
  std::vector<double> mm;
  for (std::size_t k = 0; k < inliers.size(); ++k)
  {
    const Vec3& w = points[static_cast<std::size_t>(inliers[k])].world;
    mm.push_back(hit[k] ? 1000.0 * std::hypot(hits[k].x - w.x, hits[k].y - w.y) : HUGE_VAL);
  }
  s.max_mm = *std::max_element(mm.begin(), mm.end());
  s.median_mm = median(mm);
  if (!std::isfinite(s.max_mm))
  {
    return failure("an inlier's ray does not reach the points' plane in the solution: check the correspondences");
  }
  double sum_mm = 0.0;
  for (const double d : mm)
  {
    sum_mm += d * d;
  }
  s.rms_mm = std::sqrt(sum_mm / static_cast<double>(mm.size()));

  // Uncertainty: the weak-solve limits and the expected floor error.
  cv::Mat covariance;
  if (!poseCovariance(lens, s.distortion, pose, points, inliers, 0.0, fit_k ? Extra::Distortion : Extra::None,
                      covariance))
  {
    return failure("the points do not determine the pose (singular Jacobian): spread them over the image");
  }
  double rotation_deg = 0.0, translation = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    rotation_deg = std::max(rotation_deg, std::sqrt(std::max(0.0, covariance.at<double>(k, k))) * 180.0 / M_PI);
    translation = std::max(translation, std::sqrt(std::max(0.0, covariance.at<double>(3 + k, 3 + k))));
  }
  double corner_px = 0.0;
  if (fit_k)
  {
    s.k_stddev = {std::sqrt(std::max(0.0, covariance.at<double>(6, 6))),
                  std::sqrt(std::max(0.0, covariance.at<double>(7, 7)))};
    const cv::Matx22d k_covariance = covariance(cv::Rect(6, 6, 2, 2));
    corner_px = distortionCornerStddevPx(lens, k_covariance);
  }
  if (!(rotation_deg <= options.max_rotation_stddev_deg && translation <= options.max_translation_stddev &&
        corner_px <= options.max_distortion_stddev_px))
  {
    return failure("the solve is weak (1-sigma rotation " + num(rotation_deg) + " deg, translation " +
                   num(1000.0 * translation) + " mm, distortion at the image corner " + num(corner_px) +
                   " px; limits " + num(options.max_rotation_stddev_deg) + " deg, " +
                   num(1000.0 * options.max_translation_stddev) + " mm, " + num(options.max_distortion_stddev_px) +
                   " px): use more points spread over the image, with less noise");
  }
  expectedErrors(lens, s.distortion, pose, covariance, points, inliers, "point", s.expected, s.warnings);
  s.ok = true;
  return s;
}
}  // namespace rviz_projector
