// Test-only camera simulator for the structured-light tests: a projector lights the floor with a
// pattern, a camera on the robot photographs it. Independent of the code under test: OpenCV's
// cv::undistortPoints (camera) and cv::projectPoints (projector) and plain matrix maths only.
//
// Per camera pixel, ss x ss sub-samples: raw pixel -> cv::undistortPoints (camera K, D) -> ray in the
// base frame -> floor z = 0 -> cv::projectPoints (true projector pose, K, D) -> the pattern's pixel
// there (nearest; dark outside the image). Captured value = 255 (ambient + gain * mean lit), then a
// Gaussian blur (camera optics) and Gaussian noise (fixed seed), rounded and saturated to 8 bits.
// Optionally a checkerboard stands on the floor (Scene::board, for --board): a rectangle at a pose,
// printed with albedo (white squares and margin 0.85, black 0.08) that scales the light it
// reflects; a ray meets it before the floor behind it, and it shadows the floor from the projector.
// Plain ray-rectangle maths, written here.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/rigid_transform.h"

namespace rviz_projector
{
namespace sim
{
struct Lens
{
  int width = 0;
  int height = 0;
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  std::vector<double> D;  ///< plumb_bob (k1, k2, p1, p2, k3); empty: none

  cv::Matx33d K() const { return cv::Matx33d(fx, 0, cx, 0, fy, cy, 0, 0, 1); }
  cv::Mat distortion() const { return D.empty() ? cv::Mat::zeros(1, 5, CV_64F) : cv::Mat(D, true).reshape(1, 1); }
};

/// p_base = R p_optical + t.
struct Pose
{
  cv::Matx33d R = cv::Matx33d::eye();
  cv::Vec3d t;
};

/// Mount as projector.launch takes it (R = Rz(yaw) Ry(pitch) Rx(roll), positive pitch down), then
/// body -> optical (z forward along body x, x right = body -y, y down = body -z). Written out here
/// rather than taken from the core so that the simulation does not share its conventions' code.
inline Pose mountPose(double x, double y, double z, double roll, double pitch, double yaw)
{
  const double cr = std::cos(roll), sr = std::sin(roll), cp = std::cos(pitch), sp = std::sin(pitch);
  const double cyaw = std::cos(yaw), syaw = std::sin(yaw);
  const cv::Matx33d rx(1, 0, 0, 0, cr, -sr, 0, sr, cr);
  const cv::Matx33d ry(cp, 0, sp, 0, 1, 0, -sp, 0, cp);
  const cv::Matx33d rz(cyaw, -syaw, 0, syaw, cyaw, 0, 0, 0, 1);
  // Columns: optical x, y, z in body coordinates.
  const cv::Matx33d body_optical(0, 0, 1, -1, 0, 0, 0, -1, 0);
  Pose pose;
  pose.R = rz * ry * rx * body_optical;
  pose.t = cv::Vec3d(x, y, z);
  return pose;
}

/// A printed checkerboard: its frame (x along the corner columns, y along the rows, z its normal)
/// in the base frame with the origin at the first inner corner; inner corners cols x rows, squares
/// of `square` metres from (-square, -square) to (cols square, rows square), a white margin around.
struct Board
{
  bool present = false;
  Pose pose;
  int cols = 7;
  int rows = 5;
  double square = 0.06;
  double margin = 0.03;
  double white = 0.85;
  double black = 0.08;

  /// Albedo at board coordinates (x, y); -1 off the board.
  double albedo(double x, double y) const
  {
    const double lo = -square - margin;
    if (x < lo || y < lo || x > cols * square + margin || y > rows * square + margin)
    {
      return -1.0;
    }
    if (x < -square || y < -square || x >= cols * square || y >= rows * square)
    {
      return white;
    }
    const int i = int(std::floor(x / square)) + 1, j = int(std::floor(y / square)) + 1;
    return (i + j) % 2 == 0 ? black : white;
  }

  /// Ray origin + s direction meets the board (s > 0): s, and the board coordinates; false if not.
  bool hit(const cv::Vec3d& origin, const cv::Vec3d& direction, double& s, double& x, double& y) const
  {
    if (!present)
    {
      return false;
    }
    const cv::Vec3d n(pose.R(0, 2), pose.R(1, 2), pose.R(2, 2));
    const double along = n.dot(direction);
    if (std::abs(along) < 1e-12)
    {
      return false;
    }
    s = n.dot(pose.t - origin) / along;
    if (!(s > 0.0))
    {
      return false;
    }
    const cv::Vec3d local = pose.R.t() * (origin + s * direction - pose.t);
    x = local[0];
    y = local[1];
    return albedo(x, y) >= 0.0;
  }
};

/// A board of `cols` x `rows` inner corners standing on the floor tilted `tilt` (radians) from it,
/// its centre `ahead` metres ahead of the base origin at lateral offset `side`, facing the robot
/// (its normal towards -x and up), its lowest edge 1 cm above the floor.
inline Board standingBoard(double ahead, double side, double tilt, int cols = 7, int rows = 5, double square = 0.06)
{
  Board b;
  b.present = true;
  b.cols = cols;
  b.rows = rows;
  b.square = square;
  // x across (base -y), y up the slope and away (cos tilt, 0, sin tilt), z = x cross y.
  const cv::Vec3d bx(0.0, -1.0, 0.0), by(std::cos(tilt), 0.0, std::sin(tilt)), bz = bx.cross(by);
  b.pose.R = cv::Matx33d(bx[0], by[0], bz[0], bx[1], by[1], bz[1], bx[2], by[2], bz[2]);
  const double low = -square - b.margin;  // the lowest board y
  const double centre_y = 0.5 * (rows - 1) * square;
  const double centre_z = 0.01 + (centre_y - low) * std::sin(tilt);
  const cv::Vec3d centre(ahead, side, centre_z);
  b.pose.t = centre - bx * (0.5 * (cols - 1) * square) - by * centre_y;
  return b;
}

struct Scene
{
  Lens projector;
  Pose projector_pose;
  Lens camera;
  Pose camera_pose;
  int supersample = 4;
  double ambient = 0.2;     ///< of full scale, on the floor whatever the projector shows
  double gain = 0.7;        ///< full-scale fraction added by a white projector pixel
  double blur_sigma = 1.0;  ///< camera pixels
  double noise_sigma = 2.0; ///< grey levels
  Board board;              ///< none unless present
};

/// The demo's projector (1280x800, fx = fy = 1900, cx = 640, cy = 750) 1.2 m up, 0.15 m ahead,
/// pitched down 0.876 rad; a 640x480 camera (fx = fy = 500, k1 = -0.1) beside it that sees the patch.
inline Scene demoScene(bool wide_angle_projector)
{
  Scene scene;
  scene.projector = Lens{1280, 800, 1900.0, 1900.0, 640.0, 750.0, {}};
  if (wide_angle_projector)
  {
    scene.projector.D = {-0.2, 0.05, 0.0, 0.0, 0.0};
  }
  scene.projector_pose = mountPose(0.15, 0.0, 1.2, 0.0, 0.876, 0.0);
  scene.camera = Lens{640, 480, 500.0, 500.0, 322.5, 237.0, {-0.1, 0.0, 0.0, 0.0, 0.0}};
  scene.camera_pose = mountPose(0.1, 0.05, 1.3, 0.01, 0.72, -0.02);
  return scene;
}

/// Rotation vector and translation of the base frame in a lens's optical frame (what
/// cv::projectPoints takes).
inline void opticalFromBase(const Pose& base_T_optical, cv::Vec3d& rvec, cv::Vec3d& tvec)
{
  const cv::Matx33d r = base_T_optical.R.t();
  cv::Rodrigues(r, rvec);
  tvec = -(r * base_T_optical.t);
}

/// Pixels of base-frame points through the true projector (pose and distortion).
inline std::vector<cv::Point2d> projectWithProjector(const Scene& scene, const std::vector<cv::Point3d>& points)
{
  cv::Vec3d rvec, tvec;
  opticalFromBase(scene.projector_pose, rvec, tvec);
  std::vector<cv::Point2d> pixels;
  cv::projectPoints(points, rvec, tvec, scene.projector.K(), scene.projector.distortion(), pixels);
  return pixels;
}

class Camera
{
public:
  explicit Camera(const Scene& scene) : scene_(scene)
  {
    const int ss = scene.supersample;
    const int w = scene.camera.width, h = scene.camera.height;
    std::vector<cv::Point2d> raw;
    raw.reserve(std::size_t(w) * std::size_t(h) * std::size_t(ss * ss));
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        for (int j = 0; j < ss; ++j)
        {
          for (int i = 0; i < ss; ++i)
          {
            raw.emplace_back(x + (i + 0.5) / ss - 0.5, y + (j + 0.5) / ss - 0.5);
          }
        }
      }
    }
    std::vector<cv::Point2d> normalised;
    cv::undistortPoints(raw, normalised, scene.camera.K(), scene.camera.distortion(), cv::noArray(), cv::noArray(),
                        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));
    std::vector<cv::Point3d> floor;
    std::vector<std::size_t> which;
    const cv::Matx33d p_r = scene.projector_pose.R.t();
    albedo_.assign(raw.size(), 1.0f);
    const Board& board = scene.board;
    for (std::size_t k = 0; k < normalised.size(); ++k)
    {
      const cv::Vec3d d = scene.camera_pose.R * cv::Vec3d(normalised[k].x, normalised[k].y, 1.0);
      double s = -scene.camera_pose.t[2] / d[2];
      double bs = 0.0, bx = 0.0, by = 0.0;
      const bool on_board = board.hit(scene.camera_pose.t, d, bs, bx, by) && (!(d[2] < 0.0) || bs < s);
      if (on_board)
      {
        s = bs;
        albedo_[k] = float(board.albedo(bx, by));
      }
      else if (!(d[2] < 0.0) || !(s > 0.0))
      {
        continue;
      }
      const cv::Vec3d p = scene.camera_pose.t + s * d;
      // The projector's light: the board's face towards it, and no board between it and the floor.
      const cv::Vec3d to_point = p - scene.projector_pose.t;
      double ps = 0.0, px = 0.0, py = 0.0;
      if (on_board)
      {
        const cv::Vec3d n(board.pose.R(0, 2), board.pose.R(1, 2), board.pose.R(2, 2));
        if (n.dot(scene.projector_pose.t - p) * n.dot(scene.camera_pose.t - p) <= 0.0)
        {
          continue;  // lit from behind
        }
      }
      else if (board.hit(scene.projector_pose.t, to_point, ps, px, py) && ps < 1.0 - 1e-9)
      {
        continue;  // in the board's shadow
      }
      // In front of the projector and within a sane field (its distortion polynomial is only
      // meaningful near the image).
      const cv::Vec3d q = p_r * (p - scene.projector_pose.t);
      if (!(q[2] > 0.0) || std::hypot(q[0] / q[2], q[1] / q[2]) > 1.5)
      {
        continue;
      }
      floor.emplace_back(p[0], p[1], p[2]);
      which.push_back(k);
    }
    const std::vector<cv::Point2d> pixels = projectWithProjector(scene, floor);
    index_.assign(raw.size(), -1);
    for (std::size_t n = 0; n < which.size(); ++n)
    {
      const double u = std::floor(pixels[n].x + 0.5), v = std::floor(pixels[n].y + 0.5);
      if (u >= 0 && v >= 0 && u < scene.projector.width && v < scene.projector.height)
      {
        index_[which[n]] = int(v) * scene.projector.width + int(u);
      }
    }
  }

  /// The same geometry under other light (ambient, gain): no new ray tracing.
  Camera withLight(double ambient, double gain) const
  {
    Camera other(*this);
    other.scene_.ambient = ambient;
    other.scene_.gain = gain;
    return other;
  }

  /// The capture of one projected frame (CV_8UC1, projector size); `seed` makes the noise.
  cv::Mat capture(const cv::Mat& pattern, std::uint64_t seed) const
  {
    const int ss2 = scene_.supersample * scene_.supersample;
    const int w = scene_.camera.width, h = scene_.camera.height;
    cv::Mat light(h, w, CV_32F);
    const uchar* p = pattern.ptr<uchar>(0);  // generated patterns are continuous
    std::size_t k = 0;
    for (int y = 0; y < h; ++y)
    {
      float* row = light.ptr<float>(y);
      for (int x = 0; x < w; ++x)
      {
        double sum = 0.0;
        for (int s = 0; s < ss2; ++s, ++k)
        {
          sum += albedo_[k] * (scene_.ambient + scene_.gain * (index_[k] >= 0 ? p[index_[k]] : 0) / 255.0);
        }
        row[x] = float(255.0 * sum / ss2);
      }
    }
    if (scene_.blur_sigma > 0.0)
    {
      cv::GaussianBlur(light, light, cv::Size(0, 0), scene_.blur_sigma);
    }
    if (scene_.noise_sigma > 0.0)
    {
      cv::Mat noise(h, w, CV_32F);
      cv::RNG rng(seed);
      rng.fill(noise, cv::RNG::NORMAL, 0.0, scene_.noise_sigma);
      light += noise;
    }
    cv::Mat out;
    light.convertTo(out, CV_8U);  // rounds and saturates
    return out;
  }

private:
  Scene scene_;
  std::vector<int> index_;  ///< per sub-sample: projector pixel index, -1 where unlit
  std::vector<float> albedo_;  ///< per sub-sample: 1 on the floor, the board's print on it
};
/// The camera of demoScene(wide_angle_projector), traced once per test process and lens (tracing
/// 640x480 x 16 sub-pixels is the slow part, several seconds under the sanitizers); withLight()
/// gives it other light.
inline const Camera& demoCamera(bool wide_angle_projector)
{
  static const Camera pinhole(demoScene(false));
  static const Camera wide(demoScene(true));
  return wide_angle_projector ? wide : pinhole;
}

/// The lens as a CameraInfo gives it (K = P, plumb_bob D), in the core's type.
inline LensCalibration calibrationOf(const Lens& lens)
{
  LensCalibration c;
  c.width = std::uint32_t(lens.width);
  c.height = std::uint32_t(lens.height);
  c.distortion_model = "plumb_bob";
  c.D = lens.D.empty() ? std::vector<double>(5, 0.0) : lens.D;
  c.K = {lens.fx, 0, lens.cx, 0, lens.fy, lens.cy, 0, 0, 1};
  c.P = {lens.fx, 0, lens.cx, 0, 0, lens.fy, lens.cy, 0, 0, 0, 1, 0};
  return c;
}

/// The pose in the core's type (p_base = R p_optical + t).
inline RigidTransform transformOf(const Pose& pose)
{
  std::array<double, 9> r{};
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      r[std::size_t(3 * i + j)] = pose.R(i, j);
    }
  }
  return RigidTransform::fromMatrix(r, Vec3{pose.t[0], pose.t[1], pose.t[2]});
}
}  // namespace sim
}  // namespace rviz_projector
