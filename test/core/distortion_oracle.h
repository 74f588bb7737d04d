// Test oracle for the distortion-fitting mount solvers: a projector with a distorting lens, by
// OpenCV used directly (cv::projectPoints for floor point -> raw pixel, cv::undistortPoints for
// raw pixel -> ray) and the hand-built mount rotation of mount_test_oracle.h. Nothing here calls
// the solvers' code.
#pragma once

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "mount_test_oracle.h"
#include "rviz_projector/core/mount_solver.h"

namespace distortion_oracle
{
using mount_oracle::Mount;
using rviz_projector::FloorPoint;
using rviz_projector::Vec2;
using rviz_projector::Vec3;

struct Lens
{
  int width = 1280, height = 800;
  double fx = 1900, fy = 1900, cx = 640, cy = 750;
  std::vector<double> d{0, 0, 0, 0, 0};  // k1, k2, p1, p2, k3
  cv::Matx33d k() const { return {fx, 0, cx, 0, fy, cy, 0, 0, 1}; }
  rviz_projector::PinholeModel model() const
  {
    return {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), fx, fy, cx, cy};
  }
};

inline Lens lensWith(double k1, double k2)
{
  Lens lens;
  lens.d = {k1, k2, 0, 0, 0};
  return lens;
}

/// OpenCV's pose of the mount: p_optical = R p_parent + t.
inline void pose(const Mount& m, cv::Vec3d& rvec, cv::Vec3d& tvec)
{
  const mount_oracle::Mat r = mount_oracle::parentROptical(m);
  const cv::Matx33d optical_R_parent(r[0][0], r[1][0], r[2][0], r[0][1], r[1][1], r[2][1], r[0][2], r[1][2], r[2][2]);
  cv::Rodrigues(optical_R_parent, rvec);
  tvec = -(optical_R_parent * cv::Vec3d(m.x, m.y, m.z));
}

/// Where the raw pixel's ray meets z = 0 (cv::undistortPoints, hand rotation); false when it does
/// not, or further than max_distance from the point below the projector.
inline bool floorOf(const Lens& lens, const Mount& m, const Vec2& pixel, Vec3& out, double max_distance = 8.0)
{
  std::vector<cv::Point2d> in{{pixel.x, pixel.y}}, ideal;
  cv::undistortPoints(in, ideal, lens.k(), lens.d, cv::noArray(), cv::noArray(),
                      cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-14));
  // Beyond a fold the iteration lands elsewhere: keep only pixels it inverts exactly.
  std::vector<cv::Point2d> back;
  cv::projectPoints(std::vector<cv::Point3d>{{ideal[0].x, ideal[0].y, 1.0}}, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0),
                    lens.k(), lens.d, back);
  if (!(std::hypot(back[0].x - pixel.x, back[0].y - pixel.y) < 1e-6))
    return false;
  const mount_oracle::Mat r = mount_oracle::parentROptical(m);
  const double ray[3] = {ideal[0].x, ideal[0].y, 1.0};
  double d[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      d[i] += r[i][k] * ray[k];
  if (!(d[2] < -1e-9))
    return false;
  const double s = -m.z / d[2];
  out = {m.x + s * d[0], m.y + s * d[1], 0.0};
  return std::hypot(out.x - m.x, out.y - m.y) <= max_distance;
}

/// The raw pixel of a floor point (cv::projectPoints).
inline Vec2 pixelOf(const Lens& lens, const Mount& m, const Vec3& w)
{
  cv::Vec3d rvec, tvec;
  pose(m, rvec, tvec);
  std::vector<cv::Point2d> px;
  cv::projectPoints(std::vector<cv::Point3d>{{w.x, w.y, w.z}}, rvec, tvec, lens.k(), lens.d, px);
  return {px[0].x, px[0].y};
}

enum class Noise
{
  None,
  Uniform,   ///< +-0.5 px (quantisation)
  Gaussian,  ///< sigma 0.3 px
};

struct Options
{
  double step = 8.0;           ///< pixel grid step over the image
  Noise noise = Noise::Uniform;
  double gaussian_sigma = 0.3;
  double outliers = 0.03;      ///< fraction replaced by a random pixel at least 20 px off
  unsigned seed = 1;
  double u0 = 0, u1 = 1e9, v0 = 0, v1 = 1e9;  ///< only pixels in this box
};

/// Floor points on a grid of pixels over the lit area: floor point = the pixel's ray on the floor,
/// projector pixel = cv::projectPoints of the floor point + noise; a fraction replaced by outliers.
inline std::vector<FloorPoint> correspondences(const Lens& lens, const Mount& m, const Options& o)
{
  std::mt19937 random(o.seed);
  std::uniform_real_distribution<double> uniform(-0.5, 0.5);
  std::normal_distribution<double> gaussian(0.0, o.gaussian_sigma);
  std::uniform_real_distribution<double> fraction(0.0, 1.0);
  std::vector<FloorPoint> out;
  int id = 0;
  for (double v = o.step / 2; v < lens.height - 0.5; v += o.step)
  {
    for (double u = o.step / 2; u < lens.width - 0.5; u += o.step)
    {
      if (u < o.u0 || u > o.u1 || v < o.v0 || v > o.v1)
        continue;
      Vec3 w;
      if (!floorOf(lens, m, {u, v}, w))
        continue;
      Vec2 p = pixelOf(lens, m, w);
      if (o.noise == Noise::Uniform)
        p = {p.x + uniform(random), p.y + uniform(random)};
      else if (o.noise == Noise::Gaussian)
        p = {p.x + gaussian(random), p.y + gaussian(random)};
      if (fraction(random) < o.outliers)
      {
        Vec2 q;
        do
        {
          q = {fraction(random) * (lens.width - 1), fraction(random) * (lens.height - 1)};
        } while (std::hypot(q.x - p.x, q.y - p.y) < 20.0);
        p = q;
      }
      p.x = std::clamp(p.x, -0.5, lens.width - 0.5);
      p.y = std::clamp(p.y, -0.5, lens.height - 0.5);
      out.push_back({id++, p, w});
    }
  }
  return out;
}

struct FloorError
{
  double median_mm = 0, max_mm = 0;
  int count = 0;
};

/// Floor distance between where the true and the fitted projector put the pixels of a 40 x 25 grid
/// over the image (those the truth puts on the floor within 8 m).
inline FloorError floorError(const Lens& truth, const Mount& true_mount, const Lens& fitted, const Mount& fitted_mount)
{
  std::vector<double> mm;
  for (int j = 0; j < 25; ++j)
  {
    for (int i = 0; i < 40; ++i)
    {
      const Vec2 px{(i + 0.5) * truth.width / 40.0 - 0.5, (j + 0.5) * truth.height / 25.0 - 0.5};
      Vec3 a, b;
      if (!floorOf(truth, true_mount, px, a))
        continue;
      if (!floorOf(fitted, fitted_mount, px, b, 1e9))
      {
        mm.push_back(HUGE_VAL);
        continue;
      }
      mm.push_back(1000.0 * std::hypot(a.x - b.x, a.y - b.y));
    }
  }
  FloorError e;
  e.count = static_cast<int>(mm.size());
  if (mm.empty())
    return e;
  std::sort(mm.begin(), mm.end());
  e.median_mm = mm[mm.size() / 2];
  e.max_mm = mm.back();
  return e;
}

/// Distance between two mounts' optical centres, metres.
inline double positionError(const Mount& a, const Mount& b)
{
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}
}  // namespace distortion_oracle
