// Mount solver: the pose covariance and the expected floor error it implies (see mount_solver.h).
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
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
/// Step of the numerical floor-point Jacobian (radians of the rotation vector, metres).
constexpr double kStep = 1e-6;
/// Distance ahead of the mount at which the expected error is reported, metres.
constexpr double kAhead = 2.0;

/// d(u, v) / d(x, y) at each inlier: how a measurement error on its plane moves its pixel.
std::vector<cv::Matx22d> pixelsPerMetre(const PinholeModel& lens, const std::vector<double>& coefficients,
                                        const Pose& pose, const std::vector<FloorPoint>& points,
                                        const std::vector<int>& inliers)
{
  const double d = 1e-3;
  std::vector<cv::Point3d> probes;
  for (int i : inliers)
  {
    const Vec3& w = points[static_cast<std::size_t>(i)].world;
    probes.emplace_back(w.x - d, w.y, w.z);
    probes.emplace_back(w.x + d, w.y, w.z);
    probes.emplace_back(w.x, w.y - d, w.z);
    probes.emplace_back(w.x, w.y + d, w.z);
  }
  std::vector<cv::Point2d> px;
  cv::projectPoints(probes, pose.rvec, pose.tvec, cameraMatrix(lens), coefficients, px);
  std::vector<cv::Matx22d> out;
  for (std::size_t k = 0; k + 3 < px.size(); k += 4)
  {
    const cv::Point2d dx = (px[k + 1] - px[k]) / (2 * d);
    const cv::Point2d dy = (px[k + 3] - px[k + 2]) / (2 * d);
    out.emplace_back(dx.x, dy.x, dx.y, dy.y);
  }
  return out;
}

/// The model with parameter k (rvec 0..2, tvec 3..5, k1 6, k2 7) moved by delta.
void perturbed(const Pose& pose, const std::vector<double>& coefficients, int k, double delta, Pose& p,
               std::vector<double>& c)
{
  p = pose;
  c = coefficients;
  if (k < 6)
  {
    (k < 3 ? p.rvec[k] : p.tvec[k - 3]) += delta;
  }
  else
  {
    c[static_cast<std::size_t>(k - 6)] += delta;
  }
}

LensDistortion distortionOf(const LensDistortion& model, const std::vector<double>& coefficients)
{
  return LensDistortion(model.none() ? LensDistortion::Model::PlumbBob : model.model(), coefficients);
}

/// 1-sigma radial error (mm) of the point where `pixel`'s ray meets z = plane_z; NaN when it does
/// not. `covariance`: 6 x 6 (pose) or 8 x 8 (pose, k1, k2).
double floorErrorMm(const PinholeModel& lens, const LensDistortion& distortion, const Pose& pose,
                    const cv::Mat& covariance, const Vec2& pixel, double plane_z)
{
  const int n = covariance.rows;
  const std::vector<double> coefficients = coefficientsOf(distortion);
  cv::Mat g(2, n, CV_64F);
  for (int k = 0; k < n; ++k)
  {
    Vec3 plus, minus;
    Pose p;
    std::vector<double> c;
    perturbed(pose, coefficients, k, kStep, p, c);
    const bool ok_plus = pixelOnPlane(lens, distortionOf(distortion, c), parentTOptical(p), pixel, plane_z, plus);
    perturbed(pose, coefficients, k, -kStep, p, c);
    if (!ok_plus || !pixelOnPlane(lens, distortionOf(distortion, c), parentTOptical(p), pixel, plane_z, minus))
    {
      return std::nan("");
    }
    g.at<double>(0, k) = (plus.x - minus.x) / (2 * kStep);
    g.at<double>(1, k) = (plus.y - minus.y) / (2 * kStep);
  }
  const cv::Mat c = g * covariance * g.t();
  return 1000.0 * std::sqrt(std::max(0.0, c.at<double>(0, 0) + c.at<double>(1, 1)));
}
}  // namespace

bool poseCovariance(const PinholeModel& lens, const LensDistortion& distortion, const Pose& pose,
                    const std::vector<FloorPoint>& points, const std::vector<int>& inliers, double tape_error,
                    Extra extra, cv::Mat& covariance)
{
  const std::vector<cv::Point3d> object = objectPoints(points, inliers);
  const std::vector<double> coefficients = coefficientsOf(distortion);
  std::vector<cv::Point2d> projected;
  cv::Mat jacobian;
  cv::projectPoints(object, pose.rvec, pose.tvec, cameraMatrix(lens), coefficients, projected, jacobian);
  // Jacobian columns: rvec 0..2, tvec 3..5, fx fy 6..7, cx cy 8..9, the distortion from 10.
  cv::Mat j;
  if (extra == Extra::Distortion)
  {
    cv::hconcat(jacobian.colRange(0, 6), jacobian.colRange(10, 12), j);
  }
  else
  {
    j = jacobian.colRange(0, extra == Extra::Intrinsics ? 10 : 6);
  }
  const int params = j.cols;
  const int n = static_cast<int>(inliers.size());
  // The measurement error (metres, per coordinate on the plane): estimated from the residuals on
  // the plane, never below tape_error.
  std::vector<Vec3> hits;
  std::vector<bool> hit;
  pointsOnPlanes(lens, distortion, parentTOptical(pose), points, inliers, hits, hit);
  double sum_sq = 0.0;
  for (std::size_t k = 0; k < inliers.size(); ++k)
  {
    const Vec3& w = points[static_cast<std::size_t>(inliers[k])].world;
    if (!hit[k])
    {
      return false;
    }
    sum_sq += (hits[k].x - w.x) * (hits[k].x - w.x) + (hits[k].y - w.y) * (hits[k].y - w.y);
  }
  const double posterior = 2 * n > params ? sum_sq / (2 * n - params) : 0.0;
  const double sigma2 = std::max(posterior, tape_error * tape_error);
  // The estimator minimises pixel residuals, the noise is on the plane: sandwich covariance
  // H^-1 (J^T S J) H^-1, H = J^T J, S the pixel covariance sigma^2 A A^T of each point.
  cv::Mat h_inverse;
  if (cv::invert(j.t() * j, h_inverse, cv::DECOMP_CHOLESKY) == 0.0)
  {
    return false;
  }
  const std::vector<cv::Matx22d> a = pixelsPerMetre(lens, coefficients, pose, points, inliers);
  cv::Mat middle = cv::Mat::zeros(params, params, CV_64F);
  for (int i = 0; i < n; ++i)
  {
    const cv::Matx22d s = sigma2 * a[static_cast<std::size_t>(i)] * a[static_cast<std::size_t>(i)].t();
    const cv::Mat ji = j.rowRange(2 * i, 2 * i + 2);
    middle += ji.t() * cv::Mat(s) * ji;
  }
  covariance = h_inverse * middle * h_inverse;
  return true;
}

void expectedErrors(const PinholeModel& lens, const LensDistortion& distortion, const Pose& pose,
                    const cv::Mat& covariance, const std::vector<FloorPoint>& points,
                    const std::vector<int>& inliers, const std::string& what, std::vector<ExpectedError>& expected,
                    std::vector<std::string>& warnings)
{
  const RigidTransform transform = parentTOptical(pose);
  // The extreme crosshairs: smallest / largest u + v and u - v.
  struct Corner
  {
    const char* name;
    double su, sv;
  };
  const Corner corners[4] = {{"top left", -1, -1}, {"top right", 1, -1}, {"bottom left", -1, 1}, {"bottom right", 1, 1}};
  std::vector<int> used;
  for (const Corner& corner : corners)
  {
    int best = -1;
    double best_score = -HUGE_VAL;
    for (int i : inliers)
    {
      const Vec2& p = points[static_cast<std::size_t>(i)].pixel;
      const double score = corner.su * p.x + corner.sv * p.y;
      if (score > best_score)
      {
        best = i, best_score = score;
      }
    }
    if (best < 0 || std::find(used.begin(), used.end(), best) != used.end())
    {
      continue;
    }
    used.push_back(best);
    const FloorPoint& p = points[static_cast<std::size_t>(best)];
    ExpectedError e;
    e.where = what + " " + std::to_string(p.id) + " (" + corner.name + ")";
    if (!pixelOnPlane(lens, distortion, transform, p.pixel, p.world.z, e.world))
    {
      continue;
    }
    e.mm = floorErrorMm(lens, distortion, pose, covariance, p.pixel, p.world.z);
    if (std::isfinite(e.mm))
    {
      expected.push_back(e);
    }
  }

  const ProjectorMount mount = mountOfOpticalPose(transform);
  const Vec3 ahead{mount.x + kAhead * std::cos(mount.yaw), mount.y + kAhead * std::sin(mount.yaw), 0.0};
  std::vector<cv::Point2d> px;
  cv::projectPoints(std::vector<cv::Point3d>{{ahead.x, ahead.y, ahead.z}}, pose.rvec, pose.tvec, cameraMatrix(lens),
                    coefficientsOf(distortion), px);
  cv::Matx33d r;
  cv::Rodrigues(pose.rvec, r);
  const double depth = (r * cv::Vec3d(ahead.x, ahead.y, ahead.z) + pose.tvec)[2];
  const Vec2 pixel{px[0].x, px[0].y};
  const bool in_image = depth > 0.0 && pixel.x >= -0.5 && pixel.y >= -0.5 && pixel.x <= lens.width() - 0.5 &&
                        pixel.y <= lens.height() - 0.5;
  const double mm = in_image ? floorErrorMm(lens, distortion, pose, covariance, pixel, 0.0) : std::nan("");
  if (std::isfinite(mm))
  {
    expected.push_back({"2 m ahead", ahead, mm});
  }
  else
  {
    std::ostringstream s;
    s << "the floor 2 m ahead of the mount (" << ahead.x << ", " << ahead.y
      << ") is not in the projector's image: no expected error reported there";
    warnings.push_back(s.str());
  }
}
}  // namespace mount_solver_detail
}  // namespace rviz_projector
