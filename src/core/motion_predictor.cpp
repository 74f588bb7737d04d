#include "rviz_projector/core/motion_predictor.h"

#include "rviz_projector/core/angle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace rviz_projector
{
namespace
{
constexpr double kPi = 3.14159265358979323846;
/// Samples kept at most (0.25 s of tf at 200 Hz); the vector is reserved once: no allocation per frame.
constexpr std::size_t kCapacity = 64;
/// Stamps closer than this are the same stamp.
constexpr double kSameStamp = 1e-6;
/// Position and heading steps a jump must exceed beyond the jump speeds (tf jitter is no jump).
constexpr double kJumpSlack = 0.01;
constexpr double kJumpYawSlack = 0.02;

/// sin(t)/t and (1 - cos(t))/t, with their series near 0.
void arcFactors(double t, double& a, double& b)
{
  if (std::abs(t) < 1e-6)
  {
    a = 1.0 - t * t / 6.0;
    b = 0.5 * t;
    return;
  }
  a = std::sin(t) / t;
  b = (1.0 - std::cos(t)) / t;
}

/// SE(2) logarithm of from^-1 * to: the twist times the time (vx*dt, vy*dt, wz*dt).
PlanarTwist logRelative(const PlanarPose& from, const PlanarPose& to)
{
  const double c = std::cos(from.yaw), s = std::sin(from.yaw);
  const double dx = to.x - from.x, dy = to.y - from.y;
  const double bx = c * dx + s * dy, by = -s * dx + c * dy;  // in `from`'s body frame
  const double th = wrapToPi(to.yaw - from.yaw);
  double a, b;
  arcFactors(th, a, b);
  const double det = a * a + b * b;  // > 0 for |th| < 2 pi
  return {(a * bx + b * by) / det, (-b * bx + a * by) / det, th};
}

double planarSpeed(const PlanarTwist& t)
{
  return std::hypot(t.vx, t.vy);
}
}  // namespace

PlanarPose integrateTwist(const PlanarPose& start, const PlanarTwist& twist, double dt)
{
  const double th = twist.wz * dt;
  double a, b;
  arcFactors(th, a, b);
  const double bx = (a * twist.vx - b * twist.vy) * dt;
  const double by = (b * twist.vx + a * twist.vy) * dt;
  const double c = std::cos(start.yaw), s = std::sin(start.yaw);
  return {start.x + c * bx - s * by, start.y + s * bx + c * by, start.yaw + th};
}

PlanarTwist twistBetween(const PlanarPose& from, const PlanarPose& to, double dt)
{
  const PlanarTwist l = logRelative(from, to);
  return {l.vx / dt, l.vy / dt, l.wz / dt};
}

PlanarPose planarPose(const RigidTransform& pose, int axis)
{
  const std::array<double, 9>& r = pose.rotation();
  const int k = std::clamp(axis, 0, 2);
  return {pose.translation().x, pose.translation().y, std::atan2(r[3 + k], r[k])};
}

int mostHorizontalAxis(const RigidTransform& pose)
{
  const std::array<double, 9>& r = pose.rotation();
  int best = 0;
  for (int k = 1; k < 3; ++k)
  {
    if (std::abs(r[6 + k]) < std::abs(r[6 + best]))  // smallest vertical part
    {
      best = k;
    }
  }
  return best;
}

RigidTransform movePlanar(const RigidTransform& pose, const PlanarPose& from, const PlanarPose& to)
{
  const double d = to.yaw - from.yaw;
  const double c = std::cos(d), s = std::sin(d);
  const std::array<double, 9>& r = pose.rotation();
  std::array<double, 9> m{};
  for (int col = 0; col < 3; ++col)  // Rz(d) * R
  {
    m[col] = c * r[col] - s * r[3 + col];
    m[3 + col] = s * r[col] + c * r[3 + col];
    m[6 + col] = r[6 + col];
  }
  const Vec3& p = pose.translation();
  const double dx = p.x - from.x, dy = p.y - from.y;
  return RigidTransform::fromMatrix(m, Vec3{to.x + c * dx - s * dy, to.y + s * dx + c * dy, p.z});
}

const char* predictionStateName(Prediction::State state)
{
  switch (state)
  {
    case Prediction::Predicted:
      return "Predicted";
    case Prediction::Limited:
      return "Limited";
    case Prediction::Stopped:
      return "Stopped";
    case Prediction::Collecting:
      return "Collecting";
    case Prediction::Jump:
      return "Jump";
    case Prediction::Gap:
      return "Gap";
    case Prediction::TooFast:
      return "TooFast";
    case Prediction::Invalid:
      return "Invalid";
    case Prediction::NoPose:
      break;
  }
  return "NoPose";
}

std::string describePrediction(const Prediction& p)
{
  char text[160];
  const double deg = p.twist.wz * 180.0 / kPi;
  switch (p.state)
  {
    case Prediction::Predicted:
      std::snprintf(text, sizeof(text), "predicting %.0f ms ahead, %.2f m/s, %.1f deg/s", p.horizon * 1e3, p.speed,
                    deg);
      return text;
    case Prediction::Limited:
      std::snprintf(text, sizeof(text), "predicting %.0f ms ahead (%.0f ms wanted: Max prediction), %.2f m/s, %.1f deg/s",
                    p.horizon * 1e3, p.wanted * 1e3, p.speed, deg);
      return text;
    case Prediction::Stopped:
      return "robot stands: nothing to predict";
    case Prediction::Collecting:
      return "collecting poses: no prediction yet";
    case Prediction::Jump:
      return "off: the pose jumped (relocalisation or teleport)";
    case Prediction::Gap:
      // No age in the text: it would change with every frame while tf is silent (and each change of a
      // property repaints rviz's whole property tree).
      return "off: no new pose (gap in the motion data)";
    case Prediction::TooFast:
      std::snprintf(text, sizeof(text), "off: %.2f m/s, %.0f deg/s is faster than a robot drives", p.speed, deg);
      return text;
    case Prediction::Invalid:
      return "off: the motion data or the clock holds NaN/Inf";
    case Prediction::NoPose:
      break;
  }
  return "no pose";
}

MotionPredictor::MotionPredictor(const MotionLimits& limits) : limits_(limits)
{
  samples_.reserve(kCapacity);
}

void MotionPredictor::clear()
{
  samples_.clear();
  jumped_ = false;
  have_floor_ = false;
}

bool MotionPredictor::isJump(const Sample& from, const Sample& to) const
{
  const double dt = std::abs(to.stamp - from.stamp);
  const Vec3 d = to.pose.translation() - from.pose.translation();
  const double yaw = std::abs(wrapToPi(to.planar.yaw - from.planar.yaw));
  return norm(d) > limits_.jump_speed * dt + kJumpSlack || yaw > limits_.jump_yaw_rate * dt + kJumpYawSlack;
}

void MotionPredictor::restart(const Sample& sample)
{
  samples_.clear();
  samples_.push_back(sample);
  floor_stamp_ = sample.stamp;
  have_floor_ = true;
}

MotionPredictor::Added MotionPredictor::add(double stamp, const RigidTransform& pose)
{
  const Vec3& t = pose.translation();
  bool finite = std::isfinite(stamp) && isFinite(t);
  for (double v : pose.rotation())
  {
    finite = finite && std::isfinite(v);
  }
  if (!finite)
  {
    return Added::NotFinite;
  }
  if (samples_.empty())
  {
    axis_ = mostHorizontalAxis(pose);
  }
  const Sample sample{stamp, pose, planarPose(pose, axis_)};
  if (samples_.empty())
  {
    samples_.push_back(sample);
    return Added::Appended;
  }
  const double newest = samples_.back().stamp;
  if (have_floor_ && stamp < floor_stamp_ - kSameStamp)
  {
    return Added::TooOld;
  }
  if (stamp > newest + kSameStamp)
  {
    if (stamp - newest > limits_.max_gap)
    {
      jumped_ = false;
      restart(sample);
      return Added::AfterGap;
    }
    if (isJump(samples_.back(), sample))
    {
      jumped_ = true;
      restart(sample);
      return Added::Jump;
    }
    if (samples_.size() == kCapacity)
    {
      samples_.erase(samples_.begin());
    }
    samples_.push_back(sample);
    // Forget what is older than a gap before the newest (keeps the vector short).
    while (samples_.size() > 3 && samples_.front().stamp < stamp - limits_.max_gap)
    {
      samples_.erase(samples_.begin());
    }
    return Added::Appended;
  }
  // Not newer than the newest: a duplicate, or out of order.
  auto at = std::lower_bound(samples_.begin(), samples_.end(), stamp - kSameStamp,
                             [](const Sample& s, double v) { return s.stamp < v; });
  if (at != samples_.end() && std::abs(at->stamp - stamp) <= kSameStamp)
  {
    return Added::Duplicate;
  }
  if (stamp < newest - limits_.max_gap || samples_.size() == kCapacity)
  {
    return Added::TooOld;
  }
  if ((at != samples_.begin() && isJump(*(at - 1), sample)) || isJump(sample, *at))
  {
    return Added::TooOld;  // does not fit between its neighbours: a stale pose from before a jump
  }
  samples_.insert(at, sample);
  return Added::Inserted;
}

bool MotionPredictor::stands() const
{
  const Sample& newest = samples_.back();
  for (std::size_t i = samples_.size() - 1; i-- > 0;)
  {
    const Sample& s = samples_[i];
    const Vec3 d = s.pose.translation() - newest.pose.translation();
    if (norm(d) > limits_.stop_distance || std::abs(wrapToPi(s.planar.yaw - newest.planar.yaw)) > limits_.stop_angle)
    {
      return false;
    }
    if (newest.stamp - s.stamp >= limits_.stop_time)
    {
      return true;  // unmoved for long enough
    }
  }
  return false;
}

bool MotionPredictor::tooFast(const PlanarTwist& twist) const
{
  return planarSpeed(twist) > limits_.max_speed || std::abs(twist.wz) > limits_.max_yaw_rate;
}

PlanarTwist MotionPredictor::fit() const
{
  // Least squares of log(newest^-1 * sample) = twist * (t_sample - t_newest): exact for a
  // constant twist, and averaging out jitter over the window.
  const Sample& newest = samples_.back();
  const std::size_t n = samples_.size();
  double sum_tt = 0.0;
  PlanarTwist sum;
  for (std::size_t k = 1; k < n; ++k)
  {
    const Sample& s = samples_[n - 1 - k];
    const double tau = s.stamp - newest.stamp;  // < 0
    if (k >= 3 && tau < -limits_.window)
    {
      break;
    }
    const PlanarTwist l = logRelative(newest.planar, s.planar);
    sum.vx += tau * l.vx;
    sum.vy += tau * l.vy;
    sum.wz += tau * l.wz;
    sum_tt += tau * tau;
  }
  return {sum.vx / sum_tt, sum.vy / sum_tt, sum.wz / sum_tt};
}

bool MotionPredictor::prepare(double now, double target, Prediction& p) const
{
  if (samples_.empty())
  {
    p.state = Prediction::NoPose;
    return false;
  }
  const Sample& newest = samples_.back();
  p.pose = newest.pose;
  p.newest = newest.stamp;
  p.age = now - newest.stamp;
  p.wanted = target - newest.stamp;
  if (!std::isfinite(now) || std::isnan(target) || target == -std::numeric_limits<double>::infinity())
  {
    p.state = Prediction::Invalid;  // +Inf is a target too far: cut at the max horizon
    return false;
  }
  if (p.age > limits_.max_gap)
  {
    p.state = Prediction::Gap;
    return false;
  }
  if (samples_.size() < 2)
  {
    p.state = jumped_ ? Prediction::Jump : Prediction::Collecting;
    return false;
  }
  return true;
}

void MotionPredictor::extrapolate(Prediction& p, double max_horizon, const PlanarPose& from,
                                  const PlanarTwist& twist) const
{
  p.twist = twist;
  p.speed = planarSpeed(twist);
  if (tooFast(twist))
  {
    p.state = Prediction::TooFast;
    return;
  }
  const double limit = std::max(0.0, max_horizon);
  p.horizon = std::clamp(p.wanted, 0.0, limit);
  p.state = p.wanted > limit ? Prediction::Limited : Prediction::Predicted;
  p.pose = movePlanar(p.pose, from, integrateTwist(from, twist, p.horizon));
}

Prediction MotionPredictor::predict(double now, double target, double max_horizon) const
{
  Prediction p;
  if (!prepare(now, target, p))
  {
    return p;
  }
  if (stands())
  {
    p.state = Prediction::Stopped;
    return p;
  }
  extrapolate(p, max_horizon, samples_.back().planar, fit());
  return p;
}

Prediction MotionPredictor::predictWithTwist(double now, double target, double max_horizon, const RigidTransform& base,
                                             const PlanarTwist& base_twist) const
{
  Prediction p;
  if (!prepare(now, target, p) && p.state != Prediction::Collecting)
  {
    return p;  // one fresh pose is enough with a twist given, but not just after a jump
  }
  bool finite = std::isfinite(base_twist.vx) && std::isfinite(base_twist.vy) && std::isfinite(base_twist.wz) &&
                isFinite(base.translation());
  for (double v : base.rotation())
  {
    finite = finite && std::isfinite(v);
  }
  if (!finite)
  {
    p.state = Prediction::Invalid;
    return p;
  }
  const double slow = limits_.stop_distance / limits_.stop_time;
  if (planarSpeed(base_twist) <= slow && std::abs(base_twist.wz) <= limits_.stop_angle / limits_.stop_time)
  {
    p.state = Prediction::Stopped;
    return p;
  }
  // The twist is the base's: move the projector's pose by the motion that takes the base along it.
  extrapolate(p, max_horizon, planarPose(base, 0), base_twist);
  return p;
}
}  // namespace rviz_projector
