// Intrinsics, pose and k1, k2 from the floor and a tilted board; see two_plane_lens_fit.h.
#include "rviz_projector/core/two_plane_lens_fit.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

#include <opencv2/calib3d.hpp>

#include "mount_solver_internal.h"

namespace rviz_projector
{
using namespace mount_solver_detail;

namespace
{
constexpr int kMinFloorPoints = 100;
constexpr int kMaxRounds = 5;
/// calibrateCamera's cost grows faster than linearly with the points of a view (measured: 3,750
/// points ~3 s a call, 16,000 over 30 s): each round fits on at most this many of each plane's
/// inliers, evenly spread (every k-th); the outlier rule still judges every point.
constexpr std::size_t kMaxFloorFit = 1500;
constexpr std::size_t kMaxBoardFit = 1000;
const cv::TermCriteria kCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, DBL_EPSILON);

TwoPlaneLensFit failure(const std::string& error)
{
  TwoPlaneLensFit f;
  f.error = error;
  return f;
}

struct Model
{
  cv::Matx33d k;  ///< unshifted
  std::vector<double> d;
  cv::Vec3d rvec, tvec;
  cv::Mat stddev;  ///< calibrateCamera's stdDeviationsIntrinsics
};

/// calibrateCamera on the points `which`; false when it throws or gives nothing finite. `model.stddev`
/// is computed from the residuals of `which` only.
bool calibrate(const PinholeModel& lens, const std::vector<FloorPoint>& points, const std::vector<int>& which,
               bool fit_k, Model& model)
{
  const double ox = lens.width(), oy = lens.height();
  std::vector<std::vector<cv::Point3f>> object(1);
  std::vector<std::vector<cv::Point2f>> image(1);
  for (int i : which)
  {
    const FloorPoint& p = points[std::size_t(i)];
    object[0].emplace_back(float(p.world.x), float(p.world.y), float(p.world.z));
    image[0].emplace_back(float(p.pixel.x + ox), float(p.pixel.y + oy));
  }
  cv::Mat k = (cv::Mat_<double>(3, 3) << model.k(0, 0), 0.0, model.k(0, 2) + ox, 0.0, model.k(1, 1),
               model.k(1, 2) + oy, 0.0, 0.0, 1.0);
  cv::Mat d(model.d, true);
  int flags = cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_K3 | cv::CALIB_FIX_K4 | cv::CALIB_FIX_K5 |
              cv::CALIB_FIX_K6;
  flags |= fit_k ? cv::CALIB_ZERO_TANGENT_DIST : (cv::CALIB_FIX_K1 | cv::CALIB_FIX_K2 | cv::CALIB_FIX_TANGENT_DIST);
  if (model.d.size() == 8)
  {
    flags |= cv::CALIB_RATIONAL_MODEL;
  }
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat extrinsic_stddev, errors;
  try
  {
    cv::calibrateCamera(object, image, cv::Size(3 * int(lens.width()), 3 * int(lens.height())), k, d, rvecs, tvecs,
                        model.stddev, extrinsic_stddev, errors, flags, kCriteria);
  }
  catch (const cv::Exception&)
  {
    return false;
  }
  if (rvecs.size() != 1 || !cv::checkRange(k) || !cv::checkRange(d))
  {
    return false;
  }
  model.k = cv::Matx33d(k.at<double>(0, 0), 0.0, k.at<double>(0, 2) - ox, 0.0, k.at<double>(1, 1),
                        k.at<double>(1, 2) - oy, 0.0, 0.0, 1.0);
  d.reshape(1, 1).copyTo(model.d);
  cv::Mat r, t;
  rvecs[0].convertTo(r, CV_64F);
  tvecs[0].convertTo(t, CV_64F);
  model.rvec = cv::Vec3d(r.ptr<double>());
  model.tvec = cv::Vec3d(t.ptr<double>());
  // calibrateCamera works in float: the pose once more in double precision.
  cv::Mat rd(model.rvec), td(model.tvec);
  cv::solvePnPRefineLM(objectPoints(points, which), imagePoints(points, which), cv::Mat(model.k), model.d, rd, td,
                       kCriteria);
  model.rvec = cv::Vec3d(rd.ptr<double>());
  model.tvec = cv::Vec3d(td.ptr<double>());
  return true;
}

std::vector<double> errorsOf(const Model& model, const std::vector<FloorPoint>& points)
{
  std::vector<cv::Point3d> object;
  for (const FloorPoint& p : points)
  {
    object.emplace_back(p.world.x, p.world.y, p.world.z);
  }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(object, model.rvec, model.tvec, model.k, model.d, projected);
  cv::Matx33d r;
  cv::Rodrigues(model.rvec, r);
  std::vector<double> errors(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const double z = (r * cv::Vec3d(object[i].x, object[i].y, object[i].z) + model.tvec)[2];
    errors[i] = z > 0.0 ? std::hypot(projected[i].x - points[i].pixel.x, projected[i].y - points[i].pixel.y) : HUGE_VAL;
  }
  return errors;
}
}  // namespace

TwoPlaneLensFit fitLensOnTwoPlanes(const PinholeModel& prior, const LensDistortion& distortion,
                                   const RigidTransform& parent_T_optical, const std::vector<FloorPoint>& floor,
                                   const std::vector<FloorPoint>& board, const TwoPlaneLensOptions& options)
{
  if (const std::string problem = solverLensProblem(prior); !problem.empty())
  {
    return failure(problem);
  }
  if (board.size() < std::size_t(options.min_board_points) || floor.size() < std::size_t(kMinFloorPoints))
  {
    return failure("fitting the lens needs at least " + std::to_string(options.min_board_points) +
                   " points on the board and " + std::to_string(kMinFloorPoints) + " on the floor, got " +
                   std::to_string(board.size()) + " and " + std::to_string(floor.size()) +
                   ": put the board where the projector lights it and the camera sees it, larger or nearer");
  }
  std::vector<FloorPoint> points(floor);
  points.insert(points.end(), board.begin(), board.end());
  const std::size_t floor_count = floor.size();

  Model model;
  model.k = cameraMatrix(prior);
  model.d = coefficientsOf(distortion);
  if (options.fit_distortion)
  {
    model.d = {model.d[0], model.d[1], 0.0, 0.0, 0.0};
  }
  const Pose start = poseOf(parent_T_optical);
  model.rvec = start.rvec;
  model.tvec = start.tvec;

  // Outliers: from the start model (the dense floor solution with the prior lens, which misses the
  // board by the prior's error), with a threshold wide enough for that error, then as the rule says.
  std::vector<int> inliers;
  double threshold = 64.0;
  for (int round = 0; round < kMaxRounds; ++round)
  {
    const std::vector<double> errors = errorsOf(model, points);
    if (round > 0)
    {
      threshold = std::max(options.outlier_px, options.outlier_median_factor * median(errors));
    }
    std::vector<int> next;
    for (std::size_t i = 0; i < errors.size(); ++i)
    {
      if (errors[i] <= threshold)
      {
        next.push_back(int(i));
      }
    }
    if (round > 1 && next == inliers)
    {
      break;
    }
    inliers = next;
    const long board_inliers = std::count_if(inliers.begin(), inliers.end(), [&](int i) { return std::size_t(i) >= floor_count; });
    if (board_inliers < options.min_board_points || long(inliers.size()) - board_inliers < kMinFloorPoints)
    {
      return failure("only " + std::to_string(board_inliers) + " board points and " +
                     std::to_string(inliers.size() - std::size_t(board_inliers)) + " floor points agree with one "
                     "lens and mount within " + num(threshold) + " px (at least " +
                     std::to_string(options.min_board_points) + " and " + std::to_string(kMinFloorPoints) +
                     " needed): check the board's size (--board) and that it is flat");
    }
    std::vector<int> floor_part, board_part;
    for (int i : inliers)
    {
      (std::size_t(i) < floor_count ? floor_part : board_part).push_back(i);
    }
    std::vector<int> fit;
    for (const auto& [part, cap] : {std::make_pair(&floor_part, kMaxFloorFit), std::make_pair(&board_part, kMaxBoardFit)})
    {
      const double step = std::max(1.0, double(part->size()) / double(cap));
      for (double k = 0.0; k < double(part->size()); k += step)
      {
        fit.push_back((*part)[std::size_t(k)]);
      }
    }
    if (!calibrate(prior, points, fit, options.fit_distortion, model))
    {
      return failure("fitting the lens (cv::calibrateCamera) failed: check the board's size (--board)");
    }
  }

  TwoPlaneLensFit f;
  f.lens = PinholeModel(prior.width(), prior.height(), model.k(0, 0), model.k(1, 1), model.k(0, 2), model.k(1, 2));
  if (const std::string problem = solverLensProblem(f.lens); !problem.empty())
  {
    return failure("the fitted lens is unusable: " + problem);
  }
  f.distortion = options.fit_distortion ? radialDistortion(model.d[0], model.d[1]) : distortion;
  const Pose pose{model.rvec, model.tvec};
  f.parent_T_optical = parentTOptical(pose);
  f.mount = mountOfOpticalPose(f.parent_T_optical);
  const double floor_z = floor.front().world.z;
  if (!(f.parent_T_optical.translation().z > floor_z))
  {
    return failure("the fitted lens puts the projector at or below the floor");
  }
  if (const LensDistortion::Fold fold = f.distortion.foldCheck(f.lens.cornerRadius()); fold.folds)
  {
    return failure("the fitted " + LensDistortion::foldError(fold, f.lens.cornerRadius()));
  }
  for (int k = 0; k < 4; ++k)
  {
    f.lens_stddev[std::size_t(k)] = model.stddev.at<double>(k);
  }
  if (options.fit_distortion)
  {
    f.k_stddev = {model.stddev.at<double>(4), model.stddev.at<double>(5)};
  }
  const double focal = std::max(f.lens_stddev[0] / f.lens.fx(), f.lens_stddev[1] / f.lens.fy());
  const double principal = std::max(f.lens_stddev[2] / f.lens.width(), f.lens_stddev[3] / f.lens.height());
  if (!(focal <= options.max_focal_stddev && principal <= options.max_principal_stddev))
  {
    return failure("the lens fit is weak (1-sigma focal length " + num(100.0 * focal) + " %, principal point " +
                   num(100.0 * principal) + " % of the image; limits " + num(100.0 * options.max_focal_stddev) +
                   " %, " + num(100.0 * options.max_principal_stddev) + " %): use a larger board, tilted more");
  }

  // Residuals.
  const std::vector<double> errors = errorsOf(model, points);
  double sum = 0.0, board_sum = 0.0;
  std::vector<int> floor_inliers;
  for (int i : inliers)
  {
    sum += errors[std::size_t(i)] * errors[std::size_t(i)];
    if (std::size_t(i) >= floor_count)
    {
      board_sum += errors[std::size_t(i)] * errors[std::size_t(i)];
      ++f.board_inliers;
    }
    else
    {
      floor_inliers.push_back(i);
    }
  }
  f.floor_inliers = int(floor_inliers.size());
  f.outliers = int(points.size() - inliers.size());
  f.rms_px = std::sqrt(sum / double(inliers.size()));
  f.board_rms_px = std::sqrt(board_sum / double(f.board_inliers));
  std::vector<Vec3> hits;
  std::vector<bool> hit;
  pointsOnPlanes(f.lens, f.distortion, f.parent_T_optical, points, floor_inliers, hits, hit);
  std::vector<double> mm;
  double sum_mm = 0.0;
  for (std::size_t k = 0; k < floor_inliers.size(); ++k)
  {
    const Vec3& w = points[std::size_t(floor_inliers[k])].world;
    mm.push_back(hit[k] ? 1000.0 * std::hypot(hits[k].x - w.x, hits[k].y - w.y) : HUGE_VAL);
    sum_mm += mm.back() * mm.back();
  }
  f.floor_max_mm = *std::max_element(mm.begin(), mm.end());
  f.floor_median_mm = median(mm);
  f.floor_rms_mm = std::sqrt(sum_mm / double(mm.size()));
  if (!std::isfinite(f.floor_max_mm))
  {
    return failure("a floor point's ray does not reach the floor in the fitted lens: check the correspondences");
  }
  f.ok = true;
  return f;
}
}  // namespace rviz_projector
