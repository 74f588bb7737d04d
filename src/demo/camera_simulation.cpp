// CameraSimulation: see camera_simulation.h. Written without the project's core on purpose (this is
// the world the calibration is checked against).
#include "camera_simulation.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace rviz_projector_demo
{
namespace
{
constexpr int kMaxImageSide = 8192;
// Undistortion: iterate until the ray projects back within this many pixels (or 100 iterations).
const cv::TermCriteria kUndistortCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-10);
constexpr float kOutside = -100.0f;  // a map value outside any image: remap's border, black

bool finite(double value)
{
  return std::isfinite(value);
}

cv::Matx33d cameraMatrix(const LensParameters& lens)
{
  return cv::Matx33d(lens.fx, 0.0, lens.cx, 0.0, lens.fy, lens.cy, 0.0, 0.0, 1.0);
}

cv::Mat distortion(const LensParameters& lens)
{
  if (lens.D.empty())
  {
    return cv::Mat::zeros(1, 5, CV_64F);
  }
  return cv::Mat(lens.D, true).reshape(1, 1);
}

void checkLens(const LensParameters& lens, const std::string& name, std::ostringstream& problems)
{
  if (!finite(lens.fx) || !finite(lens.fy) || !(lens.fx > 0.0) || !(lens.fy > 0.0))
  {
    problems << name << " fx and fy must be finite and positive (" << lens.fx << ", " << lens.fy << "). ";
  }
  if (!finite(lens.cx) || !finite(lens.cy))
  {
    problems << name << " cx and cy must be finite. ";
  }
  const std::size_t n = lens.D.size();
  if (n != 0 && n != 4 && n != 5 && n != 8)
  {
    problems << name << " D must have 0, 4, 5 (plumb_bob) or 8 (rational_polynomial) values, not " << n << ". ";
  }
  if (!std::all_of(lens.D.begin(), lens.D.end(), finite))
  {
    problems << name << " D must be finite. ";
  }
}

void checkMount(const MountPose& m, const std::string& name, std::ostringstream& problems)
{
  if (!finite(m.x) || !finite(m.y) || !finite(m.z) || !finite(m.roll) || !finite(m.pitch) || !finite(m.yaw))
  {
    problems << name << " x y z roll pitch yaw must be finite. ";
  }
}
cv::Matx33d mountRotation(const MountPose& mount)
{
  const double cr = std::cos(mount.roll), sr = std::sin(mount.roll);
  const double cp = std::cos(mount.pitch), sp = std::sin(mount.pitch);
  const double cy = std::cos(mount.yaw), sy = std::sin(mount.yaw);
  const cv::Matx33d rz(cy, -sy, 0.0, sy, cy, 0.0, 0.0, 0.0, 1.0);
  const cv::Matx33d ry(cp, 0.0, sp, 0.0, 1.0, 0.0, -sp, 0.0, cp);
  const cv::Matx33d rx(1.0, 0.0, 0.0, 0.0, cr, -sr, 0.0, sr, cr);
  return rz * ry * rx;
}

/// The board's geometry: where a ray meets it, and its print.
struct BoardGeometry
{
  BoardSettings settings;
  cv::Matx33d r;  ///< columns: the board's axes in the base frame
  cv::Vec3d centre;

  explicit BoardGeometry(const BoardSettings& b)
    : settings(b), r(mountRotation(b.pose)), centre(b.pose.x, b.pose.y, b.pose.z)
  {
  }
  cv::Vec3d normal() const { return cv::Vec3d(r(0, 2), r(1, 2), r(2, 2)); }

  /// Albedo at board coordinates relative to its centre; -1 off the board.
  double albedo(double x, double y) const
  {
    const BoardSettings& b = settings;
    // Coordinates from the first inner corner.
    const double u = x + 0.5 * (b.cols - 1) * b.square, v = y + 0.5 * (b.rows - 1) * b.square;
    const double lo = -b.square - b.margin;
    if (u < lo || v < lo || u > b.cols * b.square + b.margin || v > b.rows * b.square + b.margin)
    {
      return -1.0;
    }
    if (u < -b.square || v < -b.square || u >= b.cols * b.square || v >= b.rows * b.square)
    {
      return b.white;
    }
    const int i = static_cast<int>(std::floor(u / b.square)) + 1, j = static_cast<int>(std::floor(v / b.square)) + 1;
    return (i + j) % 2 == 0 ? b.black : b.white;
  }

  /// origin + t direction on the board (t > 0): t and the albedo there; false if it misses.
  bool hit(const cv::Vec3d& origin, const cv::Vec3d& direction, double& t, double& albedo_out) const
  {
    if (!settings.present)
    {
      return false;
    }
    const cv::Vec3d n = normal();
    const double along = n.dot(direction);
    if (std::abs(along) < 1e-12)
    {
      return false;
    }
    t = n.dot(centre - origin) / along;
    if (!(t > 0.0))
    {
      return false;
    }
    const cv::Vec3d local = r.t() * (origin + t * direction - centre);
    albedo_out = albedo(local[0], local[1]);
    return albedo_out >= 0.0;
  }
};
}  // namespace

cv::Matx33d opticalRotation(const MountPose& mount)
{
  // Columns: optical x = -body y, optical y = -body z, optical z = body x.
  const cv::Matx33d body_optical(0.0, 0.0, 1.0, -1.0, 0.0, 0.0, 0.0, -1.0, 0.0);
  return mountRotation(mount) * body_optical;
}

std::string checkSettings(const CameraSimulationSettings& s)
{
  std::ostringstream problems;
  if (s.width < 1 || s.height < 1 || s.width > kMaxImageSide || s.height > kMaxImageSide)
  {
    problems << "camera width and height must be 1.." << kMaxImageSide << " (" << s.width << "x" << s.height << "). ";
  }
  checkLens(s.camera, "camera", problems);
  checkLens(s.projector, "projector", problems);
  checkMount(s.camera_mount, "camera", problems);
  checkMount(s.projector_mount, "projector", problems);
  if (finite(s.camera_mount.z) && !(s.camera_mount.z > 0.0))
  {
    problems << "the camera must be above the floor (z = " << s.camera_mount.z << "). ";
  }
  if (s.supersampling < 1 || s.supersampling > 4)
  {
    problems << "supersampling must be 1..4 (" << s.supersampling << "). ";
  }
  if (!finite(s.ambient) || s.ambient < 0.0 || s.ambient > 1.0)
  {
    problems << "ambient must be in [0, 1] (" << s.ambient << "). ";
  }
  if (s.board.present)
  {
    const BoardSettings& b = s.board;
    checkMount(b.pose, "board", problems);
    if (b.cols < 3 || b.rows < 3 || b.cols > 50 || b.rows > 50 || !finite(b.square) || b.square < 0.005 ||
        b.square > 0.5 || !finite(b.margin) || b.margin < 0.0 || b.margin > 1.0 || !finite(b.white) ||
        !finite(b.black) || b.white < 0.0 || b.white > 1.0 || b.black < 0.0 || b.black > 1.0)
    {
      problems << "the board needs 3..50 inner corners each way, a square of 0.005..0.5 m, a margin of 0..1 m and "
                  "albedos in [0, 1]. ";
    }
  }
  if (!finite(s.gain) || s.gain < 0.0 || s.gain > 10.0)
  {
    problems << "gain must be in [0, 10] (" << s.gain << "). ";
  }
  if (!finite(s.blur) || s.blur < 0.0 || s.blur > 50.0)
  {
    problems << "blur must be in [0, 50] pixels (" << s.blur << "). ";
  }
  if (!finite(s.noise) || s.noise < 0.0 || s.noise > 1.0)
  {
    problems << "noise must be in [0, 1] (" << s.noise << "). ";
  }
  std::string text = problems.str();
  if (!text.empty())
  {
    text.pop_back();
  }
  return text;
}

std::string projectorLuminance(const std::string& encoding, int width, int height, std::size_t step,
                               const std::uint8_t* data, std::size_t size, cv::Mat& luminance)
{
  luminance.release();
  int channels = 0;
  int conversion = -1;
  if (encoding == "mono8")
  {
    channels = 1;
  }
  else if (encoding == "rgb8")
  {
    channels = 3;
    conversion = cv::COLOR_RGB2GRAY;
  }
  else if (encoding == "bgr8")
  {
    channels = 3;
    conversion = cv::COLOR_BGR2GRAY;
  }
  else if (encoding == "rgba8")
  {
    channels = 4;
    conversion = cv::COLOR_RGBA2GRAY;
  }
  else if (encoding == "bgra8")
  {
    channels = 4;
    conversion = cv::COLOR_BGRA2GRAY;
  }
  else
  {
    return "projector image encoding '" + encoding + "' is not mono8, rgb8, bgr8, rgba8 or bgra8";
  }
  std::ostringstream why;
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
  {
    why << "projector image size " << width << "x" << height << " is not 1.." << kMaxImageSide;
    return why.str();
  }
  const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  if (step < row || size != step * static_cast<std::size_t>(height) || data == nullptr)
  {
    why << "projector image " << width << "x" << height << " " << encoding << ": step " << step << " (at least "
        << row << ") and data size " << size << " (step x height = " << step * static_cast<std::size_t>(height)
        << ") do not match";
    return why.str();
  }
  // cv::Mat does not write through a const view; the data is only read.
  const cv::Mat view(height, width, CV_8UC(channels), const_cast<std::uint8_t*>(data), step);
  if (conversion < 0)
  {
    luminance = view.clone();
  }
  else
  {
    cv::cvtColor(view, luminance, conversion);
  }
  return "";
}

CameraSimulation::CameraSimulation(const CameraSimulationSettings& settings) : settings_(settings)
{
  const std::string problems = checkSettings(settings);
  if (!problems.empty())
  {
    throw std::invalid_argument(problems);
  }
}

void CameraSimulation::buildMaps(const cv::Size& projector_size)
{
  const int s = settings_.supersampling;
  const int sub_width = settings_.width * s;
  const int sub_height = settings_.height * s;
  const cv::Matx33d camera_k = cameraMatrix(settings_.camera);
  const cv::Mat camera_d = distortion(settings_.camera);
  const cv::Matx33d camera_r = opticalRotation(settings_.camera_mount);
  const cv::Vec3d camera_c(settings_.camera_mount.x, settings_.camera_mount.y, settings_.camera_mount.z);

  const cv::Matx33d projector_k = cameraMatrix(settings_.projector);
  const cv::Mat projector_d = distortion(settings_.projector);
  const cv::Matx33d projector_r = opticalRotation(settings_.projector_mount);
  const cv::Vec3d projector_c(settings_.projector_mount.x, settings_.projector_mount.y, settings_.projector_mount.z);
  // World (base) -> projector optical: q = R^T (p - c).
  const cv::Matx33d world_to_projector = projector_r.t();
  cv::Vec3d rvec;
  cv::Rodrigues(cv::Mat(world_to_projector), rvec);
  const cv::Vec3d tvec = -(world_to_projector * projector_c);

  // The projector lens' field of view: the largest undistorted radius of its image border.
  std::vector<cv::Point2d> border;
  const double w = projector_size.width, h = projector_size.height;
  for (int i = 0; i <= 64; ++i)
  {
    const double f = i / 64.0;
    border.emplace_back(-0.5 + f * w, -0.5);
    border.emplace_back(-0.5 + f * w, h - 0.5);
    border.emplace_back(-0.5, -0.5 + f * h);
    border.emplace_back(w - 0.5, -0.5 + f * h);
  }
  std::vector<cv::Point2d> border_rays;
  cv::undistortPoints(border, border_rays, projector_k, projector_d, cv::noArray(), cv::noArray(), kUndistortCriteria);
  double max_radius2 = 0.0;
  for (const cv::Point2d& ray : border_rays)
  {
    max_radius2 = std::max(max_radius2, ray.dot(ray));
  }
  max_radius2 *= 1.05 * 1.05;

  const BoardGeometry board(settings_.board);
  albedo_ = board.settings.present ? cv::Mat(sub_height, sub_width, CV_32FC1, cv::Scalar(1.0)) : cv::Mat();
  cv::Mat map_x(sub_height, sub_width, CV_32FC1, cv::Scalar(kOutside));
  cv::Mat map_y(sub_height, sub_width, CV_32FC1, cv::Scalar(kOutside));
  std::vector<cv::Point2d> pixels(static_cast<std::size_t>(sub_width));
  std::vector<cv::Point2d> rays;
  std::vector<cv::Point3d> back_rays;
  std::vector<cv::Point2d> back;
  std::vector<cv::Point3d> floor;
  std::vector<int> columns;
  std::vector<cv::Point2d> projected;
  double residual = 0.0;
  std::size_t lit = 0;
  int first_row = sub_height, last_row = -1, first_col = sub_width, last_col = -1;
  for (int row = 0; row < sub_height; ++row)
  {
    // Sub-pixel centres: pixel i covers [i - 0.5, i + 0.5].
    const double v = (row + 0.5) / s - 0.5;
    for (int col = 0; col < sub_width; ++col)
    {
      pixels[static_cast<std::size_t>(col)] = cv::Point2d((col + 0.5) / s - 0.5, v);
    }
    cv::undistortPoints(pixels, rays, camera_k, camera_d, cv::noArray(), cv::noArray(), kUndistortCriteria);
    back_rays.clear();
    for (const cv::Point2d& ray : rays)
    {
      back_rays.emplace_back(ray.x, ray.y, 1.0);
    }
    cv::projectPoints(back_rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_k, camera_d, back);
    floor.clear();
    columns.clear();
    for (int col = 0; col < sub_width; ++col)
    {
      const std::size_t i = static_cast<std::size_t>(col);
      residual = std::max(residual, cv::norm(back[i] - pixels[i]));
      const cv::Vec3d direction = camera_r * cv::Vec3d(rays[i].x, rays[i].y, 1.0);
      double t = direction[2] < -1e-9 ? -camera_c[2] / direction[2] : HUGE_VAL;  // the floor, if below the horizon
      double board_t = 0.0, albedo = 1.0;
      const bool on_board = board.hit(camera_c, direction, board_t, albedo) && board_t < t;
      if (on_board)
      {
        t = board_t;
        albedo_.at<float>(row, col) = static_cast<float>(albedo);
      }
      if (!std::isfinite(t))
      {
        continue;  // at or above the horizon: no floor
      }
      const cv::Vec3d point = camera_c + t * direction;
      double shadow_t = 0.0, shadow_albedo = 0.0;
      if (on_board ? board.normal().dot(projector_c - point) * board.normal().dot(camera_c - point) <= 0.0
                   : board.hit(projector_c, point - projector_c, shadow_t, shadow_albedo) && shadow_t < 1.0 - 1e-9)
      {
        continue;  // the board lit from behind, or the floor in its shadow
      }
      const cv::Vec3d q = world_to_projector * (point - projector_c);
      if (!(q[2] > 1e-9))
      {
        continue;  // behind the projector
      }
      const double qx = q[0] / q[2], qy = q[1] / q[2];
      if (qx * qx + qy * qy > max_radius2)
      {
        continue;  // outside the projector lens' field of view
      }
      floor.emplace_back(point[0], point[1], on_board ? point[2] : 0.0);
      columns.push_back(col);
    }
    if (floor.empty())
    {
      continue;
    }
    cv::projectPoints(floor, rvec, tvec, projector_k, projector_d, projected);
    float* xs = map_x.ptr<float>(row);
    float* ys = map_y.ptr<float>(row);
    for (std::size_t k = 0; k < columns.size(); ++k)
    {
      const cv::Point2d& p = projected[k];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || p.x < -1.0 || p.y < -1.0 || p.x > w || p.y > h)
      {
        continue;  // outside the image (a one-pixel margin for the bilinear edge)
      }
      xs[columns[k]] = static_cast<float>(p.x);
      ys[columns[k]] = static_cast<float>(p.y);
      first_row = std::min(first_row, row);
      last_row = std::max(last_row, row);
      first_col = std::min(first_col, columns[k]);
      last_col = std::max(last_col, columns[k]);
      if (p.x >= -0.5 && p.y >= -0.5 && p.x <= w - 0.5 && p.y <= h - 0.5)
      {
        ++lit;
      }
    }
  }
  undistortion_residual_ = residual;
  lit_fraction_ = static_cast<double>(lit) / (static_cast<double>(sub_width) * sub_height);
  cv::convertMaps(map_x, map_y, map1_, map2_, CV_16SC2);
  // Only the sub-pixels that can see the projector are remapped (whole camera pixels); the rest of
  // sub_ stays black.
  sub_ = cv::Mat::zeros(sub_height, sub_width, CV_8UC1);
  lit_rect_ = cv::Rect();
  if (last_row >= 0)
  {
    const int x0 = first_col / s * s, y0 = first_row / s * s;
    const int x1 = (last_col / s + 1) * s, y1 = (last_row / s + 1) * s;
    lit_rect_ = cv::Rect(x0, y0, x1 - x0, y1 - y0);
  }
  projector_size_ = projector_size;
}

cv::Mat CameraSimulation::renderClean(const cv::Mat& luminance)
{
  const double ambient = 255.0 * settings_.ambient;
  cv::Mat clean;
  if (luminance.empty())
  {
    return cv::Mat(settings_.height, settings_.width, CV_32FC1, cv::Scalar(ambient));
  }
  if (luminance.type() != CV_8UC1)
  {
    throw std::invalid_argument("CameraSimulation::renderClean: the luminance must be CV_8UC1");
  }
  if (luminance.size() != projector_size_ || map1_.empty())
  {
    buildMaps(luminance.size());
  }
  // 8 bits until the pixel mean (each step rounds to 1/2 grey level, far below the noise): a 32-bit
  // float remap costs twice as much.
  if (lit_rect_.area() > 0)
  {
    cv::Mat lit = sub_(lit_rect_);  // remap writes into the view (same size and type)
    cv::remap(luminance, lit, map1_(lit_rect_), map2_(lit_rect_), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(0));
  }
  if (!albedo_.empty())
  {
    // With a board: the light of each sub-pixel times its albedo, then the pixel mean.
    cv::Mat light;
    sub_.convertTo(light, CV_32F, settings_.gain, ambient);
    cv::resize(light.mul(albedo_), clean, cv::Size(settings_.width, settings_.height), 0.0, 0.0, cv::INTER_AREA);
  }
  else
  {
    cv::Mat mean;
    // An integer factor: INTER_AREA is the exact mean of each pixel's sub-pixels.
    cv::resize(sub_, mean, cv::Size(settings_.width, settings_.height), 0.0, 0.0, cv::INTER_AREA);
    mean.convertTo(clean, CV_32F, settings_.gain, ambient);
  }
  if (settings_.blur > 0.0)
  {
    cv::GaussianBlur(clean, clean, cv::Size(0, 0), settings_.blur, settings_.blur, cv::BORDER_REPLICATE);
  }
  return clean;
}

cv::Mat CameraSimulation::expose(const cv::Mat& clean, cv::RNG& rng) const
{
  cv::Mat frame;
  if (settings_.noise > 0.0)
  {
    cv::Mat noise(clean.size(), CV_32FC1);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, 255.0 * settings_.noise);
    cv::Mat noisy = clean + noise;
    noisy.convertTo(frame, CV_8U);  // rounds and saturates
  }
  else
  {
    clean.convertTo(frame, CV_8U);
  }
  return frame;
}

void ExposureHistory::add(double arrival, const cv::Mat& luminance)
{
  entries_.push_back(Entry{arrival, luminance});
  while (entries_.size() > capacity_)
  {
    entries_.pop_front();
  }
}

const ExposureHistory::Entry* ExposureHistory::at(double time)
{
  for (std::size_t i = entries_.size(); i-- > 0;)
  {
    if (entries_[i].arrival <= time)
    {
      entries_.erase(entries_.begin(), entries_.begin() + static_cast<std::ptrdiff_t>(i));
      return &entries_.front();
    }
  }
  return nullptr;
}

void ExposureHistory::restart()
{
  if (entries_.empty())
  {
    return;
  }
  Entry newest = entries_.back();
  newest.arrival = -std::numeric_limits<double>::infinity();
  entries_.clear();
  entries_.push_back(newest);
}
}  // namespace rviz_projector_demo
