// Mount solver: the pose (and k1, k2) refinement shared by solveMount and solveMountDense, and the
// distortion-aware pixel -> plane rays (see mount_solver.h, dense_mount_solver.h).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "mount_solver_internal.h"
#include "rviz_projector/core/mount_solver.h"

namespace rviz_projector
{
namespace mount_solver_detail
{
namespace
{
/// The pose and k1, k2 as one parameter vector (rvec, tvec, k1, k2).
void unpack(const cv::Mat& p, Pose& pose, std::vector<double>& coefficients, bool fit_k)
{
  for (int i = 0; i < 3; ++i)
  {
    pose.rvec[i] = p.at<double>(i);
    pose.tvec[i] = p.at<double>(3 + i);
  }
  if (fit_k)
  {
    coefficients[0] = p.at<double>(6);
    coefficients[1] = p.at<double>(7);
  }
}

double squaredError(const PinholeModel& lens, const std::vector<cv::Point3d>& object,
                    const std::vector<cv::Point2d>& image, const Pose& pose, const std::vector<double>& coefficients)
{
  std::vector<cv::Point2d> projected;
  cv::projectPoints(object, pose.rvec, pose.tvec, cameraMatrix(lens), coefficients, projected);
  double sum = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i)
  {
    const cv::Point2d d = image[i] - projected[i];
    sum += d.dot(d);
  }
  return std::isfinite(sum) ? sum : HUGE_VAL;
}
}  // namespace

Pose poseOf(const RigidTransform& parent_T_optical)
{
  // p_optical = R^T (p_parent - t): rvec of R^T, tvec = -R^T t.
  const std::array<double, 9>& r = parent_T_optical.rotation();
  const cv::Matx33d optical_R_parent(r[0], r[3], r[6], r[1], r[4], r[7], r[2], r[5], r[8]);
  const Vec3& t = parent_T_optical.translation();
  Pose pose;
  cv::Rodrigues(optical_R_parent, pose.rvec);
  pose.tvec = -(optical_R_parent * cv::Vec3d(t.x, t.y, t.z));
  return pose;
}

std::vector<double> coefficientsOf(const LensDistortion& distortion)
{
  return distortion.none() ? std::vector<double>(5, 0.0) : distortion.coefficients();
}

LensDistortion radialDistortion(double k1, double k2)
{
  return LensDistortion(LensDistortion::Model::PlumbBob, {k1, k2, 0.0, 0.0, 0.0});
}

bool refinePose(const PinholeModel& lens, const std::vector<cv::Point3d>& object,
                const std::vector<cv::Point2d>& image, bool fit_k, Pose& pose, std::vector<double>& coefficients,
                int max_iterations)
{
  const int n = fit_k ? 8 : 6;
  cv::Mat p(n, 1, CV_64F);
  for (int i = 0; i < 3; ++i)
  {
    p.at<double>(i) = pose.rvec[i];
    p.at<double>(3 + i) = pose.tvec[i];
  }
  if (fit_k)
  {
    p.at<double>(6) = coefficients[0];
    p.at<double>(7) = coefficients[1];
  }
  Pose current = pose;
  std::vector<double> c = coefficients;
  double cost = squaredError(lens, object, image, current, c);
  if (!std::isfinite(cost) || object.empty())
  {
    return false;
  }
  double lambda = 1e-3;
  const cv::Matx33d k = cameraMatrix(lens);
  for (int iteration = 0; iteration < max_iterations; ++iteration)
  {
    std::vector<cv::Point2d> projected;
    cv::Mat jacobian;
    cv::projectPoints(object, current.rvec, current.tvec, k, c, projected, jacobian);
    // Normal equations over the selected columns (rvec, tvec 0..5; k1, k2 10, 11).
    cv::Mat jtj = cv::Mat::zeros(n, n, CV_64F), jtr = cv::Mat::zeros(n, 1, CV_64F);
    const int columns[8] = {0, 1, 2, 3, 4, 5, 10, 11};
    for (int row = 0; row < jacobian.rows; ++row)
    {
      const double* jr = jacobian.ptr<double>(row);
      const std::size_t i = static_cast<std::size_t>(row / 2);
      const double r = row % 2 == 0 ? image[i].x - projected[i].x : image[i].y - projected[i].y;
      double sel[8];
      for (int a = 0; a < n; ++a)
      {
        sel[a] = jr[columns[a]];
      }
      for (int a = 0; a < n; ++a)
      {
        double* out = jtj.ptr<double>(a);
        for (int b = a; b < n; ++b)
        {
          out[b] += sel[a] * sel[b];
        }
        jtr.at<double>(a) += sel[a] * r;
      }
    }
    for (int a = 0; a < n; ++a)
    {
      for (int b = 0; b < a; ++b)
      {
        jtj.at<double>(a, b) = jtj.at<double>(b, a);
      }
    }
    bool improved = false;
    double decrease = 0.0;
    while (lambda < 1e12)
    {
      cv::Mat damped = jtj.clone();
      for (int a = 0; a < n; ++a)
      {
        damped.at<double>(a, a) *= 1.0 + lambda;
      }
      cv::Mat delta;
      if (!cv::solve(damped, jtr, delta, cv::DECOMP_CHOLESKY))
      {
        lambda *= 10.0;
        continue;
      }
      Pose trial = current;
      std::vector<double> trial_c = c;
      cv::Mat q = p + delta;
      unpack(q, trial, trial_c, fit_k);
      const double trial_cost = squaredError(lens, object, image, trial, trial_c);
      if (trial_cost < cost)
      {
        decrease = cost - trial_cost;
        p = q, current = trial, c = trial_c, cost = trial_cost;
        lambda = std::max(lambda / 10.0, 1e-9);
        improved = true;
        break;
      }
      lambda *= 10.0;
    }
    if (!improved || decrease <= 1e-12 * cost)
    {
      break;
    }
  }
  if (!std::isfinite(cv::norm(current.rvec)) || !std::isfinite(cv::norm(current.tvec)) ||
      !std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v); }))
  {
    return false;
  }
  pose = current;
  coefficients = c;
  return true;
}

std::vector<double> reprojectionErrors(const PinholeModel& lens, const std::vector<double>& coefficients,
                                       const Pose& pose, const std::vector<FloorPoint>& points,
                                       const std::vector<int>& which)
{
  const std::vector<cv::Point3d> object = objectPoints(points, which);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(object, pose.rvec, pose.tvec, cameraMatrix(lens), coefficients, projected);
  cv::Matx33d r;
  cv::Rodrigues(pose.rvec, r);
  std::vector<double> errors(which.size());
  for (std::size_t k = 0; k < which.size(); ++k)
  {
    const FloorPoint& p = points[static_cast<std::size_t>(which[k])];
    const double depth = (r * cv::Vec3d(p.world.x, p.world.y, p.world.z) + pose.tvec)[2];
    const double e = std::hypot(projected[k].x - p.pixel.x, projected[k].y - p.pixel.y);
    errors[k] = depth > 0.0 && std::isfinite(e) ? e : HUGE_VAL;
  }
  return errors;
}

void pointsOnPlanes(const PinholeModel& lens, const LensDistortion& distortion, const RigidTransform& parent_T_optical,
                    const std::vector<FloorPoint>& points, const std::vector<int>& which, std::vector<Vec3>& out,
                    std::vector<bool>& hit)
{
  std::vector<Vec2> pixels;
  std::vector<double> planes;
  for (int i : which)
  {
    pixels.push_back(points[static_cast<std::size_t>(i)].pixel);
    planes.push_back(points[static_cast<std::size_t>(i)].world.z);
  }
  pixelsOnPlanes(lens, distortion, parent_T_optical, pixels, planes, out, hit);
}

void pixelsOnPlanes(const PinholeModel& lens, const LensDistortion& distortion, const RigidTransform& parent_T_optical,
                    const std::vector<Vec2>& pixels, const std::vector<double>& plane_z, std::vector<Vec3>& out,
                    std::vector<bool>& hit)
{
  std::vector<Vec2> normalised;
  normalised.reserve(pixels.size());
  for (const Vec2& p : pixels)
  {
    const Vec3 ray = lens.ray(p);
    normalised.push_back({ray.x, ray.y});
  }
  const std::vector<Vec2> ideal = distortion.undistort(normalised);
  const Vec3 origin = parent_T_optical.apply(lens.centre());
  out.assign(pixels.size(), Vec3());
  hit.assign(pixels.size(), false);
  for (std::size_t i = 0; i < pixels.size(); ++i)
  {
    const Vec3 direction = parent_T_optical.rotate({ideal[i].x, ideal[i].y, 1.0});
    if (!(std::fabs(direction.z) > 1e-12) || !isFinite(origin) || !isFinite(direction))
    {
      continue;
    }
    const double s = (plane_z[i] - origin.z) / direction.z;
    if (!(s > 0.0) || !std::isfinite(s))
    {
      continue;
    }
    out[i] = origin + direction * s;
    hit[i] = true;
  }
}

double distortionCornerStddevPx(const PinholeModel& lens, const cv::Matx22d& k_covariance)
{
  const double r = lens.cornerRadius();
  const cv::Matx21d g(std::max(lens.fx(), lens.fy()) * r * r * r, std::max(lens.fx(), lens.fy()) * std::pow(r, 5));
  return std::sqrt(std::max(0.0, (g.t() * k_covariance * g)(0, 0)));
}
}  // namespace mount_solver_detail

bool pixelOnPlane(const PinholeModel& lens, const LensDistortion& distortion, const RigidTransform& parent_T_optical,
                  const Vec2& pixel, double plane_z, Vec3& out)
{
  std::vector<Vec3> hits;
  std::vector<bool> hit;
  mount_solver_detail::pixelsOnPlanes(lens, distortion, parent_T_optical, {pixel}, {plane_z}, hits, hit);
  if (hit[0])
  {
    out = hits[0];
  }
  return hit[0];
}
}  // namespace rviz_projector
