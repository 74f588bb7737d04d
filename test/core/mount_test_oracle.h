// Test oracle for the mount solver tests: a projector mount projected by hand (textbook rotation
// matrices, the pinhole equations), independent of the solver's and the mount convention's code.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "rviz_projector/core/mount_solver.h"

namespace mount_oracle
{
using Mat = std::array<std::array<double, 3>, 3>;
constexpr double kDeg = M_PI / 180.0;

struct Lens
{
  std::uint32_t width, height;
  double fx, fy, cx, cy;
  rviz_projector::PinholeModel model() const { return {width, height, fx, fy, cx, cy}; }
};

/// config/pa503w.yaml: 1280 x 800, f = 1900, principal point (640, 817) below the image.
inline Lens pa503w() { return {1280, 800, 1900.0, 1900.0, 640.0, 817.0}; }
/// A camera-like lens, principal point in the middle of the image.
inline Lens centred() { return {1280, 800, 1000.0, 1000.0, 639.5, 399.5}; }
/// Full HD, slightly anisotropic, moderate offset.
inline Lens fullHd() { return {1920, 1080, 1500.0, 1510.0, 955.0, 1000.0}; }

struct Mount
{
  double x, y, z, roll, pitch, yaw;  // metres, radians (projector.launch's convention)
};

inline Mat mul(const Mat& a, const Mat& b)
{
  Mat c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        c[i][j] += a[i][k] * b[k][j];
  return c;
}

/// Columns: the optical axes (x right, y down, z along the beam) in the parent frame:
/// Rz(yaw) Ry(pitch) Rx(roll) times the body -> optical axes (optical z = body x, x = -body y, y = -body z).
inline Mat parentROptical(const Mount& m)
{
  const double cr = std::cos(m.roll), sr = std::sin(m.roll), cp = std::cos(m.pitch), sp = std::sin(m.pitch);
  const double cy = std::cos(m.yaw), sy = std::sin(m.yaw);
  const Mat rx{{{1, 0, 0}, {0, cr, -sr}, {0, sr, cr}}};
  const Mat ry{{{cp, 0, sp}, {0, 1, 0}, {-sp, 0, cp}}};
  const Mat rz{{{cy, -sy, 0}, {sy, cy, 0}, {0, 0, 1}}};
  const Mat body_to_optical{{{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}}};
  return mul(mul(mul(rz, ry), rx), body_to_optical);
}

/// Pixel of a parent-frame point; false when it is not in front of the lens.
inline bool project(const Lens& lens, const Mount& m, const rviz_projector::Vec3& p, rviz_projector::Vec2& pixel)
{
  const Mat r = parentROptical(m);
  const double d[3] = {p.x - m.x, p.y - m.y, p.z - m.z};
  double q[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      q[i] += r[k][i] * d[k];  // transpose: parent -> optical
  if (!(q[2] > 0.0))
    return false;
  pixel = {lens.fx * q[0] / q[2] + lens.cx, lens.fy * q[1] / q[2] + lens.cy};
  return true;
}

/// Where the ray through a pixel meets the plane z = plane_z; false when behind or parallel.
inline bool hit(const Lens& lens, const Mount& m, const rviz_projector::Vec2& pixel, double plane_z,
                rviz_projector::Vec3& out)
{
  const Mat r = parentROptical(m);
  const double ray[3] = {(pixel.x - lens.cx) / lens.fx, (pixel.y - lens.cy) / lens.fy, 1.0};
  double d[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      d[i] += r[i][k] * ray[k];
  if (!(std::fabs(d[2]) > 1e-12))
    return false;
  const double s = (plane_z - m.z) / d[2];
  if (!(s > 0.0))
    return false;
  out = {m.x + s * d[0], m.y + s * d[1], m.z + s * d[2]};
  return true;
}

/// Largest rotation angle between two mounts' optical frames, radians.
inline double rotationAngle(const Mount& a, const Mount& b)
{
  const Mat ra = parentROptical(a), rb = parentROptical(b);
  double trace = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      trace += ra[k][i] * rb[k][i];
  return std::acos(std::clamp((trace - 1.0) / 2.0, -1.0, 1.0));
}

inline Mount fromSolution(const rviz_projector::ProjectorMount& m) { return {m.x, m.y, m.z, m.roll, m.pitch, m.yaw}; }

/// The floor points of the given crosshair pixels (z = 0); false when one misses the floor or lands
/// further than max_distance from the point below the projector.
inline bool floorPoints(const Lens& lens, const Mount& m, const std::vector<rviz_projector::Vec2>& pixels,
                        std::vector<rviz_projector::FloorPoint>& out, double max_distance = 10.0)
{
  out.clear();
  int id = 1;
  for (const rviz_projector::Vec2& px : pixels)
  {
    rviz_projector::Vec3 w;
    if (!hit(lens, m, px, 0.0, w) || std::hypot(w.x - m.x, w.y - m.y) > max_distance)
      return false;
    out.push_back({id++, px, w});
  }
  return true;
}
}  // namespace mount_oracle
