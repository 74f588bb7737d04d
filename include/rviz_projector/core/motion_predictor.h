// Motion compensation (issue 14): where the projector will be when a frame's light is on the floor.
//
// A robot moves on the floor, so the projector's motion is planar: a position on the floor plane
// and a heading that turns about the fixed frame's vertical (z) axis. The predictor keeps recent
// poses of the projector in the fixed frame (from tf), fits a constant body twist (forward and
// sideways speed, yaw rate) over a short window, and moves the newest pose along that twist, as an
// exact arc, to the time the light will be on the floor. Height and tilt are taken from the newest
// pose unchanged (a planar model: pitch and roll wobble are not predicted).
//
// A constant twist is predicted exactly (the fit of an SE(2) logarithm against time is exact for
// it). What makes it safe:
//  - samples are kept in stamp order: out-of-order samples are inserted, a duplicated stamp is
//    ignored, samples with no time between them count once;
//  - a pose jump (relocalisation, a teleport in simulation: a step faster than MotionLimits'
//    jump speeds) forgets the history before it: no prediction until new samples span a fit;
//  - a gap (no sample for max_gap seconds) forgets the history too, and a newest sample older than
//    max_gap when predicting gives no prediction;
//  - a fitted speed above the sane limits gives no prediction;
//  - when the newest samples have not moved (over stop_time), the robot stands: no prediction at
//    once, whatever the older samples did (no overshoot after a stop);
//  - the extrapolation is never longer than the caller's max horizon (it is cut there).
// When there is no prediction the newest pose is returned as it is: the projector shows what tf
// says, exactly as without motion compensation.
//
// An external twist (nav_msgs/Odometry of the robot's base) can replace the fitted one:
// predictWithTwist. Times are seconds on one clock (ROS time); nothing here reads a clock.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rviz_projector/core/rigid_transform.h"

namespace rviz_projector
{
/// A pose reduced to the floor plane: position (fixed frame x, y, metres) and heading (radians,
/// about the fixed frame's z axis).
struct PlanarPose
{
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;
};

/// A body twist in the plane: velocity along the body's own planar x and y axes (m/s) and yaw rate
/// (rad/s, counter-clockwise seen from above).
struct PlanarTwist
{
  double vx = 0.0;
  double vy = 0.0;
  double wz = 0.0;
};

/// Where a body starting at `start` is after `dt` seconds of constant body twist `twist` (the exact
/// arc: SE(2) exponential).
PlanarPose integrateTwist(const PlanarPose& start, const PlanarTwist& twist, double dt);
/// The constant body twist that takes `from` to `to` in `dt` seconds (SE(2) logarithm / dt; the
/// heading change is taken in (-pi, pi]). `dt` must be > 0.
PlanarTwist twistBetween(const PlanarPose& from, const PlanarPose& to, double dt);
/// The planar pose of a 3D pose: its position's x, y and the heading of its body axis `axis`
/// (0 = x, 1 = y, 2 = z) projected on the floor (atan2 of the axis' fixed-frame y and x).
PlanarPose planarPose(const RigidTransform& pose, int axis);
/// The body axis (0, 1 or 2) of `pose` that lies most nearly horizontal: the one whose heading is
/// best defined.
int mostHorizontalAxis(const RigidTransform& pose);
/// `pose` moved by the planar rigid motion that takes `from` to `to` (a rotation about the vertical
/// by to.yaw - from.yaw and a horizontal translation): height and tilt are unchanged.
RigidTransform movePlanar(const RigidTransform& pose, const PlanarPose& from, const PlanarPose& to);

/// Tuning of MotionPredictor. The defaults suit indoor robots (up to 3 m/s, 3 rad/s) with tf at
/// 10-200 Hz.
struct MotionLimits
{
  double window = 0.12;        ///< s: samples fitted; at least the newest 3 are used when this holds fewer
  double max_gap = 0.25;       ///< s: a longer time without a sample is a gap
  double jump_speed = 5.0;     ///< m/s: a faster step between two samples is a jump
  double jump_yaw_rate = 8.0;  ///< rad/s: a faster turn between two samples is a jump
  double max_speed = 3.0;      ///< m/s: a faster fitted twist is not extrapolated
  double max_yaw_rate = 3.0;   ///< rad/s: likewise
  double stop_time = 0.04;     ///< s: the newest samples over this long unmoved mean the robot stands
  double stop_distance = 0.0005;  ///< m: "unmoved" (position)
  double stop_angle = 0.0005;     ///< rad: "unmoved" (heading)
};

/// What a prediction did.
struct Prediction
{
  enum State
  {
    Predicted,  ///< extrapolated by `horizon` seconds along `twist`
    Limited,    ///< extrapolated, but the wanted horizon was longer than the caller's max: cut there
    Stopped,    ///< the robot stands: the newest pose
    Collecting, ///< too few samples for a fit (just started, or after a jump or a gap): the newest pose
    Jump,       ///< the newest sample jumped away from the ones before: the newest pose
    Gap,        ///< the newest sample is older than max_gap: the newest pose
    TooFast,    ///< the fitted twist is faster than the limits: the newest pose
    NoPose,     ///< no sample at all: `pose` is the identity, not to be used
    Invalid     ///< the clock, the target time or a given twist/base pose is NaN/Inf: the newest pose
  };
  State state = NoPose;
  RigidTransform pose;   ///< the pose to render from
  double horizon = 0.0;  ///< s extrapolated beyond the newest sample (0 unless Predicted or Limited)
  double wanted = 0.0;   ///< s from the newest sample to the target time
  PlanarTwist twist;     ///< the fitted (or given) twist; zero when Stopped
  double speed = 0.0;    ///< m/s, the twist's planar speed
  double newest = 0.0;   ///< stamp of the newest sample
  double age = 0.0;      ///< s from the newest sample to `now`
  /// Whether `pose` is extrapolated (Predicted or Limited).
  bool extrapolated() const { return state == Predicted || state == Limited; }
};

/// A short text for a prediction: "predicting 41 ms ahead, 0.98 m/s, 28.6 deg/s", "robot stands",
/// "off: pose jump (relocalisation?)", ... (for the display's read-only status line).
std::string describePrediction(const Prediction& prediction);
/// Name of a state ("Predicted", "Jump", ...).
const char* predictionStateName(Prediction::State state);

class MotionPredictor
{
public:
  /// What add() did with a sample.
  enum class Added
  {
    Appended,    ///< newer than every sample kept
    Inserted,    ///< out of order, put in its place
    Duplicate,   ///< a sample with this stamp is kept already (within 1 microsecond): ignored
    TooOld,      ///< older than the history kept (or than the last jump or gap), or out of order and
                 ///< a jump away from the sample before it: ignored
    NotFinite,   ///< NaN/Inf stamp or pose: ignored
    Jump,        ///< a jump away from the samples before: the history before it was forgotten
    AfterGap     ///< more than max_gap after the newest: the history before it was forgotten
  };

  explicit MotionPredictor(const MotionLimits& limits = MotionLimits());

  /// Adds the pose of the projector (optical frame in the fixed frame) at `stamp`.
  Added add(double stamp, const RigidTransform& pose);
  /// Forgets every sample (fixed frame or projector frame changed, display reset).
  void clear();
  /// Samples kept.
  std::size_t size() const { return samples_.size(); }

  /// The pose at time `target`, fitted from the samples; `now` is the present (for the gap check),
  /// `max_horizon` the longest extrapolation allowed (s, >= 0).
  Prediction predict(double now, double target, double max_horizon) const;
  /// The same with the twist of the robot's base given (odometry) instead of fitted: `base` is the
  /// base's pose in the fixed frame at the newest sample's time, `base_twist` its body twist.
  Prediction predictWithTwist(double now, double target, double max_horizon, const RigidTransform& base,
                              const PlanarTwist& base_twist) const;

  const MotionLimits& limits() const { return limits_; }

private:
  struct Sample
  {
    double stamp;
    RigidTransform pose;
    PlanarPose planar;
  };
  bool isJump(const Sample& from, const Sample& to) const;
  bool stands() const;
  bool tooFast(const PlanarTwist& twist) const;
  /// Common checks of predict*: fills `p` with the newest pose; false when there is nothing to
  /// extrapolate (p.state says why).
  bool prepare(double now, double target, Prediction& p) const;
  PlanarTwist fit() const;
  /// Moves p.pose along `twist` for the allowed horizon, `from` being the planar pose of the body
  /// the twist belongs to.
  void extrapolate(Prediction& p, double max_horizon, const PlanarPose& from, const PlanarTwist& twist) const;
  void restart(const Sample& sample);

  MotionLimits limits_;
  int axis_ = 0;                  ///< the body axis whose heading is the yaw (chosen at the first sample)
  std::vector<Sample> samples_;   ///< oldest first
  bool jumped_ = false;           ///< the history starts at a jump
  double floor_stamp_ = 0.0;      ///< samples older than this are ignored (the last jump or gap)
  bool have_floor_ = false;
};
}  // namespace rviz_projector
