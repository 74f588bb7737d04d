// Robot-state cues of ProjectedPath: what the navigation goal's status (actionlib's
// GoalStatusArray, e.g. /move_base/status) and the robot's motion mean for what the floor shows,
// as a function of time: colours, the pre-motion warning's blinking, the success flash, the failed
// cross. Plain C++ (no ROS): the display converts the message and calls this.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Is a blinking cue lit at `since` seconds after it started blinking at `hz`? Lit during the first
/// half of each period (so it starts lit): frac(since * hz) < 0.5. since < 0, hz <= 0 or NaN: lit.
bool blinkOn(double since, double hz);

/// One entry of a GoalStatusArray: actionlib_msgs/GoalStatus' goal_id.id, goal_id.stamp (seconds)
/// and status (PENDING 0, ACTIVE 1, PREEMPTED 2, SUCCEEDED 3, ABORTED 4, REJECTED 5, PREEMPTING 6,
/// RECALLING 7, RECALLED 8, LOST 9).
struct GoalStatusEntry
{
  std::string id;
  double stamp = 0.0;
  std::uint8_t status = 0;
};

enum class GoalPhase
{
  None,       ///< no goal known (no topic, empty list): the cues are not changed by state
  Active,     ///< a goal is pending or being pursued (PENDING, ACTIVE, PREEMPTING, RECALLING)
  Failed,     ///< the newest goal ended without success (PREEMPTED, ABORTED, REJECTED, RECALLED, LOST)
  Succeeded,  ///< the newest goal ended in success (SUCCEEDED)
};

struct GoalSummary
{
  GoalPhase phase = GoalPhase::None;
  std::string id;  ///< the goal the phase is about (empty for None)
  double stamp = 0.0;  ///< that goal's goal_id.stamp (seconds; 0: unknown)
};

/**
 * Reduces a status list to one phase. If any goal is in progress, the phase is Active for the newest
 * such goal (largest stamp; equal stamps: the later entry). Otherwise the newest goal decides
 * (Succeeded or Failed). Unknown status codes (> 9) are ignored. Empty list (or only unknown codes):
 * None. A preempted goal beside a new active one (move_base replacing a goal) is Active.
 */
GoalSummary summarizeGoals(const std::vector<GoalStatusEntry>& entries);

/// Timing of the state cues (all seconds; Hz).
struct GoalCueParameters
{
  bool warning_enabled = false;   ///< pre-motion warning
  double warning_time = 2.0;      ///< blink at least this long before the arrows become steady
  double warning_hz = 2.0;        ///< blink frequency of the warning
  double success_flash = 0.5;     ///< after success: the destination is shown this long, then cleared
};

/// What the path cues show at one instant.
struct GoalCueFrame
{
  bool arrows = true;         ///< draw the arrows (and the turn signal)
  bool destination = true;    ///< draw the destination (circle, or cross when `cross`)
  bool cross = false;         ///< the destination is a cross (failed goal) instead of the circle
  enum class Colour
  {
    Normal,     ///< the display's own colours (Arrow color, Circle color)
    Failed,     ///< Failed color (the cross)
    Succeeded,  ///< Succeeded color (the flashing circle)
  };
  Colour colour = Colour::Normal;
  bool warning = false;  ///< inside a pre-motion warning (blinking), lit or not
  /// True when the frame may differ at a later time without new input (blinking, flash pending): the
  /// display must keep rendering frames; false: the frame is steady until the next update().
  bool animating = false;
};

/**
 * The state machine of the cues over time. Feed it each new summary (when a status message arrives)
 * with the time and whether the robot stands still; ask for the frame at any time >= the last update.
 *
 * - None: the default frame (everything drawn in Normal colours, steady).
 * - A goal becomes Active (a new id, or the same id after a terminal phase): if the warning is
 *   enabled, the robot stands still at that update and the goal was issued (its stamp) less than
 *   warning_time ago (or its stamp is 0 / in the future), a warning starts: until start + warning_time
 *   arrows and destination blink together (blinkOn(t - start, warning_hz) decides both; Normal
 *   colours), then they are steady. A warning, once started, runs its full time even if the robot
 *   starts moving (at least the warning time: the visual half of the warning). Otherwise steady.
 *   Updates that keep the same active goal change nothing (no new warning).
 * - Failed: no arrows; the destination is a steady cross in the Failed colour, until another phase.
 * - Succeeded: no arrows; the destination circle in the Succeeded colour for success_flash seconds
 *   after the update that first reported success, then nothing at all (cleared), until another phase.
 * - Time going backwards (bag loop, sim reset) restarts: the frame is computed as if the last
 *   transition happened at the new time.
 * Non-finite times are ignored (no change).
 */
class GoalCueTimeline
{
public:
  void setParameters(const GoalCueParameters& parameters) { parameters_ = parameters; }
  const GoalCueParameters& parameters() const { return parameters_; }
  /// A new status summary at `time`; `robot_still` as judged by StillnessDetector.
  void update(const GoalSummary& summary, double time, bool robot_still);
  /// Back to None (no topic, display reset).
  void clear();
  GoalCueFrame frameAt(double time) const;
  GoalPhase phase() const { return phase_; }

private:
  GoalCueParameters parameters_;
  GoalPhase phase_ = GoalPhase::None;
  std::string id_;
  double since_ = 0.0;          ///< when the current phase began
  bool warning_ = false;        ///< the current Active phase began with a warning
};

/**
 * Does the robot stand still? Fed with the robot's floor position at times (from tf). Still when the
 * positions of the last `window` seconds all lie within `tolerance` metres of the newest one and the
 * samples span at least `window` seconds; a robot seen for less than `window` counts as still (it has
 * not been seen to move). Unknown (no sample, or the newest sample older than `max_age` seconds):
 * still, so a warning is shown rather than skipped. NaN/Inf samples are ignored; out-of-order samples
 * (time before the newest) clear the history first (bag loop).
 */
class StillnessDetector
{
public:
  explicit StillnessDetector(double window = 0.5, double tolerance = 0.02, double max_age = 1.0);
  void add(const Vec2& position, double time);
  bool still(double now) const;
  void clear() { samples_.clear(); }

private:
  struct Sample
  {
    Vec2 position;
    double time;
  };
  double window_;
  double tolerance_;
  double max_age_;
  std::deque<Sample> samples_;
};
}  // namespace rviz_projector
