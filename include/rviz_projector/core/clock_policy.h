// One clock policy for every time-dependent part (issue 23). Which clock answers what:
//   - ROS time (simulated under /use_sim_time, e.g. `rosbag play --clock`): the age of data, i.e. a
//     message's or a tf's stamp against ROS now (TF timeout, the mask's scan age, the Odometry age),
//     the time motion prediction predicts for, the cue timelines (marching, blinking, the success
//     flash: a bag replayed at half speed animates at half speed, in step with the robot), and the
//     stamp of the published Image.
//   - Steady time (monotonic wall time): "no new message for N s" (Path timeout: a publisher that
//     stopped is silent in wall time whatever the clock does), how long a status stays up, and
//     everything measured on this machine: render delay, a frame's time on screen, input lag.
//     A measured delay becomes ROS seconds through rate(): under `rosbag play -r 0.5` a 20 ms
//     photon delay is 10 ms of ROS time.
//   - A backward jump of ROS time (a bag loop, `rosbag play -l`) ends an epoch: every follower
//     (poses, predictions, cue state, scans) drops what it kept from before the jump.
// ROS-free: the owner feeds it readings (ROS now, steady now), frame by frame.
#pragma once

#include <cmath>
#include <cstdint>

namespace rviz_projector
{
class ClockPolicy
{
public:
  /// ROS time counts as having jumped backwards when it is earlier than the last reading by more
  /// than this (seconds): rounding of a simulated clock is no jump.
  static constexpr double kBackwardTolerance = 1e-3;
  /// The rate is measured over at least this much steady time (seconds).
  static constexpr double kRateWindow = 0.5;
  /// A measured rate beyond this is a forward jump of ROS time, not a rate: ignored.
  static constexpr double kMaxRate = 100.0;

  /// A new reading: ROS now and steady now, seconds. Returns true when ROS time jumped backwards
  /// since the last reading (the epoch changed).
  bool update(double ros_now, double steady_now);

  double rosNow() const { return ros_now_; }
  double steadyNow() const { return steady_now_; }
  /// ROS seconds per steady second: 1 until measured (a wall clock, or a bag at -r 1), 0.5 under
  /// `rosbag play -r 0.5`, 0 while the bag is paused.
  double rate() const { return std::isfinite(fixed_rate_) ? fixed_rate_ : rate_; }
  /// A rate given instead of measured (NaN: measure it again). For a clock whose rate is known
  /// (tests that step a simulated clock by hand, whose wall-time rate means nothing).
  void fixRate(double rate) { fixed_rate_ = rate; }
  /// A delay measured in steady seconds, as ROS seconds at the measured rate.
  double rosSeconds(double steady_seconds) const { return steady_seconds * rate(); }
  /// Bumped at every backward jump; a follower keeps the epoch its state belongs to.
  std::uint64_t epoch() const { return epoch_; }
  /// Whether any reading was given.
  bool started() const { return started_; }
  /// Steady seconds since the last backward jump (infinity when there was none). Right after a
  /// jump tf is empty (rviz clears its buffer) until the bag plays it again.
  double sinceJump() const { return epoch_ == 0 ? HUGE_VAL : steady_now_ - jump_steady_; }
  /// Steady seconds since ROS time started: the first reading after zero readings (a simulated
  /// clock's first /clock, e.g. `rosbag play --clock` starting); infinity when it never was zero
  /// (a wall clock). The bag's first tf comes just after its first /clock.
  double sinceTimeStarted() const { return time_started_ ? steady_now_ - start_steady_ : HUGE_VAL; }
  /// How long a missing transform stays expected (a warning, not an error) after ROS time jumped
  /// back or started.
  static constexpr double kJumpGrace = 1.0;
  /// Within kJumpGrace of a backward jump or of ROS time starting: missing tf is expected.
  bool justStartedOrJumpedBack() const { return sinceJump() < kJumpGrace || sinceTimeStarted() < kJumpGrace; }

  /// How far ahead of ROS now a message's stamp may be and still belong to the current timeline:
  /// a bag's /clock comes in steps (rosbag play: 100 Hz of bag time) and is read a moment late, so a
  /// message replayed right after a backward jump may be stamped slightly after the clock read; one
  /// from before the jump is stamped up to a whole loop later (seconds).
  static constexpr double kTimelineSlack = 0.25;
  /// Whether a message stamped `stamp` (seconds) was sent in the timeline of ROS now `ros_now`: not
  /// a message of before a backward jump (stamped later than the jump's new time).
  static bool inCurrentTimeline(double stamp, double ros_now) { return stamp <= ros_now + kTimelineSlack; }

private:
  bool started_ = false;
  double ros_now_ = 0.0;
  double steady_now_ = 0.0;
  double anchor_ros_ = 0.0;     ///< the reading the rate window started at
  double anchor_steady_ = 0.0;
  double rate_ = 1.0;
  double fixed_rate_ = std::nan("");
  double jump_steady_ = 0.0;  ///< steady time of the last backward jump
  bool time_started_ = false;  ///< ROS time went from zero to non-zero
  double start_steady_ = 0.0;  ///< steady time it did
  std::uint64_t epoch_ = 0;
};

/// A follower's view of the clock's epochs: `changed()` is true once for each new epoch.
class EpochWatch
{
public:
  /// True when `clock` is in another epoch than at the last call (never on the first call).
  bool changed(const ClockPolicy& clock)
  {
    const bool jumped = seen_ && epoch_ != clock.epoch();
    seen_ = true;
    epoch_ = clock.epoch();
    return jumped;
  }

private:
  bool seen_ = false;
  std::uint64_t epoch_ = 0;
};
}  // namespace rviz_projector
