#include "slip_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace slip
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// S-curves: speed, yaw rate magnitude, time between switches (steps) / period (smooth).
constexpr double kSpeed = 0.7;
constexpr double kYawRate = 0.6;
constexpr double kSwitch = 2.0;
constexpr double kPeriod = 4.0;
constexpr double kStep = 5e-4;  // s: the smooth S-curve's position is integrated on this grid

/// The smooth S-curve: heading(t) = -A cos(2 pi t / T), A = kYawRate T / (2 pi); its position has
/// no closed form (Fresnel-like), so it is integrated once with Simpson's rule on a fine grid and
/// interpolated (the curve bends less than 0.02 mm between grid points).
double smoothHeading(double t)
{
  const double a = kYawRate * kPeriod / (2.0 * kPi);
  return -a * std::cos(2.0 * kPi * t / kPeriod);
}

const std::vector<Vec2>& smoothTable()
{
  static const std::vector<Vec2> table = [] {
    std::vector<Vec2> xy(static_cast<std::size_t>(120.0 / kStep) + 2);
    for (std::size_t i = 1; i < xy.size(); ++i)
    {
      const double t0 = (i - 1) * kStep, tm = t0 + kStep / 2.0, t1 = t0 + kStep;
      const double h0 = smoothHeading(t0), hm = smoothHeading(tm), h1 = smoothHeading(t1);
      xy[i].x = xy[i - 1].x + kSpeed * kStep / 6.0 * (std::cos(h0) + 4.0 * std::cos(hm) + std::cos(h1));
      xy[i].y = xy[i - 1].y + kSpeed * kStep / 6.0 * (std::sin(h0) + 4.0 * std::sin(hm) + std::sin(h1));
    }
    return xy;
  }();
  return table;
}
}  // namespace

std::string motionName(Motion m)
{
  switch (m)
  {
    case Motion::Still: return "still";
    case Motion::Turn: return "turn";
    case Motion::Straight: return "straight";
    case Motion::SCurve: return "scurve";
    case Motion::SCurveSteps: return "scurve-steps";
  }
  return "?";
}

bool parseMotion(const std::string& name, Motion& m)
{
  for (Motion candidate : {Motion::Still, Motion::Turn, Motion::Straight, Motion::SCurve, Motion::SCurveSteps})
  {
    if (motionName(candidate) == name)
    {
      m = candidate;
      return true;
    }
  }
  return false;
}

RobotState robotState(Motion m, double t)
{
  t = std::max(t, 0.0);
  RobotState s;
  switch (m)
  {
    case Motion::Still:
      s.yaw = 0.05;
      break;
    case Motion::Turn:
      s.yaw = 0.5 * t;
      s.yaw_rate = 0.5;
      break;
    case Motion::Straight:
      s.x = 1.0 * t;
      s.vx = 1.0;
      break;
    case Motion::SCurve:
    {
      const std::vector<Vec2>& table = smoothTable();
      const double u = std::min(t / kStep, static_cast<double>(table.size() - 2));
      const std::size_t i = static_cast<std::size_t>(u);
      const double f = u - static_cast<double>(i);
      s.x = table[i].x + f * (table[i + 1].x - table[i].x);
      s.y = table[i].y + f * (table[i + 1].y - table[i].y);
      s.yaw = smoothHeading(t);
      s.vx = kSpeed * std::cos(s.yaw);
      s.vy = kSpeed * std::sin(s.yaw);
      s.yaw_rate = kYawRate * std::sin(2.0 * kPi * t / kPeriod);
      break;
    }
    case Motion::SCurveSteps:
    {
      // Arcs of radius v / w: segment k turns left (k even, heading -0.6 -> +0.6) or right (k odd,
      // +0.6 -> -0.6). Each segment ends on y = 0, 2 (v / w) sin(0.6) further along x.
      const double k = std::floor(t / kSwitch);
      const double tau = t - k * kSwitch;
      const bool left = static_cast<long>(k) % 2 == 0;
      const double w = left ? kYawRate : -kYawRate;
      const double heading0 = left ? -kYawRate * kSwitch / 2.0 : kYawRate * kSwitch / 2.0;
      const double radius = kSpeed / w;  // signed
      const double x0 = k * 2.0 * (kSpeed / kYawRate) * std::sin(kYawRate * kSwitch / 2.0);
      const double heading = heading0 + w * tau;
      s.x = x0 + radius * (std::sin(heading) - std::sin(heading0));
      s.y = -radius * (std::cos(heading) - std::cos(heading0));
      s.yaw = heading;
      s.vx = kSpeed * std::cos(heading);
      s.vy = kSpeed * std::sin(heading);
      s.yaw_rate = w;
      break;
    }
  }
  return s;
}

StripePattern StripePattern::forMotion(Motion m)
{
  StripePattern p;
  switch (m)
  {
    case Motion::Still:
      // Lines at 45 deg to the row: a column error and a row error both show (~1 mm per pixel).
      p.normal_angle_ = 45.0 * kDeg;
      p.pitch_ = 0.3;
      p.x_min_ = 0.0;
      p.x_max_ = 3.0;
      p.y_min_ = -1.6;
      p.y_max_ = 1.6;
      break;
    case Motion::Turn:
      p.radial_ = true;
      p.angle_step_ = 12.0 * kDeg;
      p.r_min_ = 0.8;
      p.r_max_ = 3.0;
      break;
    case Motion::Straight:
      p.normal_angle_ = 20.0 * kDeg;
      p.pitch_ = 0.4;
      p.x_min_ = -0.5;
      p.x_max_ = 17.0;
      p.y_min_ = -1.6;
      p.y_max_ = 1.6;
      break;
    case Motion::SCurve:
    case Motion::SCurveSteps:
      p.normal_angle_ = 90.0 * kDeg;
      p.pitch_ = 0.4;
      p.x_min_ = -1.5;
      p.x_max_ = 13.0;
      p.y_min_ = -2.6;
      p.y_max_ = 2.6;
      break;
  }
  return p;
}

std::vector<Stripe> StripePattern::stripes() const
{
  std::vector<Stripe> out;
  if (radial_)
  {
    const int count = static_cast<int>(std::lround(2.0 * kPi / angle_step_));
    for (int k = 0; k < count; ++k)
    {
      const double a = k * angle_step_;
      const Vec2 dir{std::cos(a), std::sin(a)};
      out.push_back(Stripe{Vec2{centre_.x + r_min_ * dir.x, centre_.y + r_min_ * dir.y},
                           Vec2{centre_.x + r_max_ * dir.x, centre_.y + r_max_ * dir.y}});
    }
    return out;
  }
  // Lines n . p = k pitch, direction d = (-n.y, n.x), clipped along their steeper axis to the box
  // (the other coordinate may run past it a little: harmless).
  const Vec2 n{std::cos(normal_angle_), std::sin(normal_angle_)};
  const Vec2 d{-n.y, n.x};
  const double corners[4][2] = {{x_min_, y_min_}, {x_min_, y_max_}, {x_max_, y_min_}, {x_max_, y_max_}};
  double s_min = 1e9, s_max = -1e9;
  for (const auto& c : corners)
  {
    const double s = n.x * c[0] + n.y * c[1];
    s_min = std::min(s_min, s);
    s_max = std::max(s_max, s);
  }
  for (long k = static_cast<long>(std::ceil(s_min / pitch_)); k * pitch_ <= s_max; ++k)
  {
    const double s = k * pitch_;
    // Points s n + t d with y in [y_min, y_max] (lines steeper than 45 deg) or x in [x_min, x_max].
    const bool by_y = std::abs(d.y) >= std::abs(d.x);
    const double t0 = by_y ? (y_min_ - s * n.y) / d.y : (x_min_ - s * n.x) / d.x;
    const double t1 = by_y ? (y_max_ - s * n.y) / d.y : (x_max_ - s * n.x) / d.x;
    out.push_back(Stripe{Vec2{s * n.x + t0 * d.x, s * n.y + t0 * d.y}, Vec2{s * n.x + t1 * d.x, s * n.y + t1 * d.y}});
  }
  return out;
}

StripeDistance StripePattern::nearest(const Vec2& p) const
{
  StripeDistance out;
  if (radial_)
  {
    const double rx = p.x - centre_.x, ry = p.y - centre_.y;
    const double r = std::hypot(rx, ry);
    const double phi = std::atan2(ry, rx);
    const double phi_k = std::round(phi / angle_step_) * angle_step_;
    out.normal = Vec2{-std::sin(phi_k), std::cos(phi_k)};  // counter-clockwise tangent
    out.distance = out.normal.x * rx + out.normal.y * ry;  // r sin(phi - phi_k)
    out.pitch = r * angle_step_;
    return out;
  }
  out.normal = Vec2{std::cos(normal_angle_), std::sin(normal_angle_)};
  const double s = out.normal.x * p.x + out.normal.y * p.y;
  out.distance = s - std::round(s / pitch_) * pitch_;
  out.pitch = pitch_;
  return out;
}

Projector demoProjector()
{
  Projector p;
  p.fx = p.fy = 1300.0;
  p.cx = 639.5;
  p.cy = 399.5;
  p.width = 1280;
  p.height = 800;
  const double pitch = std::atan2(1.2, 1.0);
  const double c = std::cos(pitch), s = std::sin(pitch);
  p.mount_t = {0.15, 0.0, 1.2};
  // Ry(pitch) (base_link -> projector_link, positive pitch tilts x down) times the body -> optical
  // rotation (optical x = -y, y = -z, z = +x of projector_link); columns: the optical axes.
  p.mount_r = {0.0, -s, c,  //
               -1.0, 0.0, 0.0,  //
               0.0, -c, -s};
  return p;
}

bool floorPoint(const Projector& p, const RobotState& state, double u, double v, Vec2& out)
{
  const double ray_o[3] = {(u - p.cx) / p.fx, (v - p.cy) / p.fy, 1.0};
  double ray_b[3];
  for (int i = 0; i < 3; ++i)
  {
    ray_b[i] = p.mount_r[3 * i] * ray_o[0] + p.mount_r[3 * i + 1] * ray_o[1] + p.mount_r[3 * i + 2] * ray_o[2];
  }
  if (ray_b[2] >= -1e-9 || p.mount_t[2] <= 0.0)
  {
    return false;
  }
  const double lambda = -p.mount_t[2] / ray_b[2];
  const double bx = p.mount_t[0] + lambda * ray_b[0], by = p.mount_t[1] + lambda * ray_b[1];
  const double c = std::cos(state.yaw), s = std::sin(state.yaw);
  out = Vec2{state.x + c * bx - s * by, state.y + s * bx + c * by};
  return true;
}

Vec2 pointVelocity(const RobotState& state, const Vec2& p)
{
  return Vec2{state.vx - state.yaw_rate * (p.y - state.y), state.vy + state.yaw_rate * (p.x - state.x)};
}

double slipAt(const StripePattern& pattern, const RobotState& state, const Vec2& p, bool& ambiguous, double* speed)
{
  const StripeDistance d = pattern.nearest(p);
  ambiguous = std::abs(d.distance) > 0.4 * d.pitch;
  const Vec2 v = pointVelocity(state, p);
  const double along = d.normal.x * v.x + d.normal.y * v.y;
  if (speed)
  {
    *speed = std::abs(along);
  }
  return along < 0.0 ? -d.distance : d.distance;
}
}  // namespace slip
