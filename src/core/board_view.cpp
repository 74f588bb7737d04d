// The tilted checkerboard in the camera's white frame; see board_view.h.
#include "rviz_projector/core/board_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace rviz_projector
{
namespace
{
constexpr double kOnBoardSquares = 0.75;
constexpr double kNearBoardSquares = 3.0;

std::string fixed(double v, int decimals)
{
  char text[48];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}

/// The board's corner outline grown by `grow` squares, through the camera, filled.
cv::Mat outlineMask(const BoardSpec& spec, double grow, const cv::Vec3d& rvec, const cv::Vec3d& tvec,
                    const cv::Mat& k, const cv::Mat& d, cv::Size size)
{
  const double x0 = -grow * spec.square, x1 = (spec.cols - 1 + grow) * spec.square;
  const double y0 = -grow * spec.square, y1 = (spec.rows - 1 + grow) * spec.square;
  const cv::Point3d corners[] = {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
  std::vector<cv::Point3d> outline;
  constexpr int kSteps = 24;  // the distortion bends the sides
  for (int side = 0; side < 4; ++side)
  {
    const cv::Point3d& a = corners[side];
    const cv::Point3d& b = corners[(side + 1) % 4];
    for (int s = 0; s < kSteps; ++s)
    {
      outline.push_back(a + (b - a) * (double(s) / kSteps));
    }
  }
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(outline, rvec, tvec, k, d, pixels);
  std::vector<cv::Point> polygon;
  for (const cv::Point2d& p : pixels)
  {
    polygon.emplace_back(int(std::lround(p.x)), int(std::lround(p.y)));
  }
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{polygon}, cv::Scalar(255));
  return mask;
}

BoardView refused(const std::string& error)
{
  BoardView view;
  view.error = error;
  return view;
}
}  // namespace

std::string boardSpecProblem(const BoardSpec& spec)
{
  if (spec.cols < 3 || spec.rows < 3 || spec.cols > 50 || spec.rows > 50)
  {
    return "the board needs 3 to 50 inner corners each way";
  }
  if (!(spec.square >= 0.005 && spec.square <= 0.5))
  {
    return "the board's square must be 0.005 to 0.5 m";
  }
  return "";
}

bool parseBoardSpec(const std::string& text, BoardSpec& out, std::string& error)
{
  std::istringstream in(text);
  BoardSpec spec;
  char x = 0, colon = 0;
  std::string rest;
  if (!(in >> spec.cols >> x >> spec.rows >> colon >> spec.square) || (x != 'x' && x != 'X') || colon != ':' ||
      (in >> rest))
  {
    error = "'" + text + "' is not COLSxROWS:SQUARE_M (inner corners and the square's side in metres, e.g. 7x5:0.04)";
    return false;
  }
  error = boardSpecProblem(spec);
  if (!error.empty())
  {
    return false;
  }
  out = spec;
  return true;
}

BoardView findBoard(const cv::Mat& white, const LensCalibration& camera, const RigidTransform& base_T_camera,
                    const BoardSpec& spec, const BoardLimits& limits)
{
  if (const std::string problem = boardSpecProblem(spec); !problem.empty())
  {
    return refused(problem);
  }
  if (const std::string problem = cameraLensProblem(camera); !problem.empty())
  {
    return refused(problem);
  }
  if (white.empty() || white.type() != CV_8UC1)
  {
    return refused("the white frame is not an 8-bit grey image");
  }
  const std::string name = std::to_string(spec.cols) + "x" + std::to_string(spec.rows);
  std::vector<cv::Point2f> corners;
  const cv::Size pattern(spec.cols, spec.rows);
  if (!cv::findChessboardCorners(white, pattern, corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE))
  {
    return refused("the checkerboard (" + name + " inner corners) is not found in the camera's white frame: put all "
                   "of it, lit and unobstructed, in the camera's view, or check --board");
  }
  // The sub-pixel search window: under half the corners' spacing, so it holds one corner.
  double spacing = HUGE_VAL;
  for (int j = 0; j < spec.rows; ++j)
  {
    for (int i = 0; i + 1 < spec.cols; ++i)
    {
      spacing = std::min(spacing, double(cv::norm(corners[std::size_t(j * spec.cols + i + 1)] -
                                                   corners[std::size_t(j * spec.cols + i)])));
    }
  }
  const int half = std::clamp(int(0.4 * spacing), 2, 10);
  cv::cornerSubPix(white, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 100, 0.001));
  std::vector<cv::Point3d> object;
  for (int j = 0; j < spec.rows; ++j)
  {
    for (int i = 0; i < spec.cols; ++i)
    {
      object.emplace_back(i * spec.square, j * spec.square, 0.0);
    }
  }
  const cv::Mat k = (cv::Mat_<double>(3, 3) << camera.K[0], 0.0, camera.K[2], 0.0, camera.K[4], camera.K[5], 0.0, 0.0, 1.0);
  const cv::Mat d = camera.D.empty() ? cv::Mat::zeros(1, 5, CV_64F) : cv::Mat(camera.D, true).reshape(1, 1);
  std::vector<cv::Point2d> image(corners.begin(), corners.end());
  cv::Vec3d rvec, tvec;
  if (!cv::solvePnP(object, image, k, d, rvec, tvec, false, cv::SOLVEPNP_ITERATIVE))
  {
    return refused("the checkerboard's pose cannot be solved from its corners");
  }
  std::vector<cv::Point2d> reprojected;
  cv::projectPoints(object, rvec, tvec, k, d, reprojected);
  double sum = 0.0;
  for (std::size_t i = 0; i < image.size(); ++i)
  {
    const cv::Point2d e = reprojected[i] - image[i];
    sum += e.dot(e);
  }
  BoardView view;
  view.corners = corners;
  view.corner_rms_px = std::sqrt(sum / double(image.size()));
  if (!(view.corner_rms_px <= limits.max_corner_rms_px))
  {
    return refused("the checkerboard's corners do not fit a flat board of " + name + " squares of " +
                   fixed(1000.0 * spec.square, 1) + " mm (RMS " + fixed(view.corner_rms_px, 2) + " px, at most " +
                   fixed(limits.max_corner_rms_px, 2) + "): check --board, that the board is flat, and the camera's "
                   "calibration");
  }
  // The plane: normal R (0, 0, 1) and the board's centre, camera frame -> base frame.
  cv::Matx33d r;
  cv::Rodrigues(rvec, r);
  const cv::Vec3d centre_camera =
      r * cv::Vec3d(0.5 * (spec.cols - 1) * spec.square, 0.5 * (spec.rows - 1) * spec.square, 0.0) + tvec;
  const cv::Vec3d normal_camera(r(0, 2), r(1, 2), r(2, 2));
  Vec3 normal = base_T_camera.rotate(Vec3{normal_camera[0], normal_camera[1], normal_camera[2]});
  const Vec3 centre = base_T_camera.apply(Vec3{centre_camera[0], centre_camera[1], centre_camera[2]});
  if (dot(normal, base_T_camera.translation() - centre) < 0.0)
  {
    normal = normal * -1.0;  // towards the camera
  }
  normal = normal * (1.0 / norm(normal));
  view.plane = Plane{normal, dot(normal, centre)};
  view.distance = cv::norm(centre_camera);
  view.tilt_deg = std::acos(std::min(1.0, std::abs(normal.z))) * 180.0 / M_PI;
  if (!(view.tilt_deg >= limits.min_tilt_deg))
  {
    return refused("the checkerboard is tilted only " + fixed(view.tilt_deg, 1) + " deg from the floor (at least " +
                   fixed(limits.min_tilt_deg, 0) + " deg needed to fit the lens): prop it up steeper, 30-60 deg");
  }
  view.on_board = outlineMask(spec, kOnBoardSquares, rvec, tvec, k, d, white.size());
  view.near_board = outlineMask(spec, kNearBoardSquares, rvec, tvec, k, d, white.size());
  return view;
}
}  // namespace rviz_projector
