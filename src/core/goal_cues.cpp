#include "rviz_projector/core/goal_cues.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
namespace
{
enum class Kind
{
  Unknown,
  InProgress,
  Succeeded,
  Failed,
};

Kind kindOf(std::uint8_t status)
{
  switch (status)
  {
    case 0:  // PENDING
    case 1:  // ACTIVE
    case 6:  // PREEMPTING
    case 7:  // RECALLING
      return Kind::InProgress;
    case 3:  // SUCCEEDED
      return Kind::Succeeded;
    case 2:  // PREEMPTED
    case 4:  // ABORTED
    case 5:  // REJECTED
    case 8:  // RECALLED
    case 9:  // LOST
      return Kind::Failed;
    default:
      return Kind::Unknown;
  }
}
}  // namespace

bool blinkOn(double since, double hz)
{
  if (!std::isfinite(since) || !std::isfinite(hz) || since < 0.0 || !(hz > 0.0))
  {
    return true;
  }
  const double cycles = since * hz;
  return cycles - std::floor(cycles) < 0.5;
}

GoalSummary summarizeGoals(const std::vector<GoalStatusEntry>& entries)
{
  const GoalStatusEntry* newest_in_progress = nullptr;
  const GoalStatusEntry* newest = nullptr;
  for (const GoalStatusEntry& entry : entries)
  {
    const Kind kind = kindOf(entry.status);
    if (kind == Kind::Unknown)
    {
      continue;
    }
    if (!newest || !(entry.stamp < newest->stamp))
    {
      newest = &entry;  // equal stamps: the later entry
    }
    if (kind == Kind::InProgress && (!newest_in_progress || !(entry.stamp < newest_in_progress->stamp)))
    {
      newest_in_progress = &entry;
    }
  }
  GoalSummary summary;
  if (newest_in_progress)
  {
    summary.phase = GoalPhase::Active;
    summary.id = newest_in_progress->id;
    summary.stamp = newest_in_progress->stamp;
  }
  else if (newest)
  {
    summary.phase = kindOf(newest->status) == Kind::Succeeded ? GoalPhase::Succeeded : GoalPhase::Failed;
    summary.id = newest->id;
    summary.stamp = newest->stamp;
  }
  return summary;
}

void GoalCueTimeline::update(const GoalSummary& summary, double time, bool robot_still)
{
  if (!std::isfinite(time))
  {
    return;
  }
  if (summary.phase == GoalPhase::None)
  {
    clear();
    return;
  }
  if (summary.phase != phase_ || summary.id != id_)
  {
    phase_ = summary.phase;
    id_ = summary.id;
    since_ = time;
    // A goal issued longer than the warning time ago (rviz started, or the State topic set, while the
    // robot is on its way) is not new to the people around: no warning. Stamp 0 or in the future
    // (another clock): judged new.
    const bool issued_long_ago =
        std::isfinite(summary.stamp) && summary.stamp > 0.0 && time - summary.stamp >= parameters_.warning_time;
    warning_ = phase_ == GoalPhase::Active && parameters_.warning_enabled && robot_still && !issued_long_ago;
    return;
  }
  if (time < since_)
  {
    since_ = time;  // time went backwards (bag loop, simulation reset): the phase restarts now
  }
}

void GoalCueTimeline::clear()
{
  phase_ = GoalPhase::None;
  id_.clear();
  since_ = 0.0;
  warning_ = false;
}

GoalCueFrame GoalCueTimeline::frameAt(double time) const
{
  GoalCueFrame frame;
  const double elapsed = std::isfinite(time) && time > since_ ? time - since_ : 0.0;
  switch (phase_)
  {
    case GoalPhase::None:
      break;
    case GoalPhase::Active:
      if (warning_ && elapsed < parameters_.warning_time)
      {
        const bool lit = blinkOn(elapsed, parameters_.warning_hz);
        frame.arrows = lit;
        frame.destination = lit;
        frame.warning = true;
        frame.animating = true;
      }
      break;
    case GoalPhase::Failed:
      frame.arrows = false;
      frame.cross = true;
      frame.colour = GoalCueFrame::Colour::Failed;
      break;
    case GoalPhase::Succeeded:
      frame.arrows = false;
      frame.destination = elapsed < parameters_.success_flash;
      frame.colour = GoalCueFrame::Colour::Succeeded;
      frame.animating = frame.destination;
      break;
  }
  return frame;
}

StillnessDetector::StillnessDetector(double window, double tolerance, double max_age)
  : window_(window), tolerance_(tolerance), max_age_(max_age)
{
}

void StillnessDetector::add(const Vec2& position, double time)
{
  if (!isFinite(position) || !std::isfinite(time))
  {
    return;
  }
  if (!samples_.empty() && time < samples_.back().time)
  {
    samples_.clear();  // time went backwards
  }
  samples_.push_back({position, time});
  while (!samples_.empty() && (samples_.front().time < time - window_ || samples_.size() > 4096))
  {
    samples_.pop_front();
  }
}

bool StillnessDetector::still(double now) const
{
  if (samples_.empty())
  {
    return true;  // unknown: a warning is shown rather than skipped
  }
  const Sample& newest = samples_.back();
  if (std::isfinite(now) && now - newest.time > max_age_)
  {
    return true;  // stale: unknown
  }
  return std::all_of(samples_.begin(), samples_.end(),
                     [&](const Sample& s) { return distance(s.position, newest.position) <= tolerance_; });
}
}  // namespace rviz_projector
