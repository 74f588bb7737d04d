// One part for "a plan replayed right after ROS time jumps back is drawn" (a bag looping or started
// again: `rosbag play -l`, a simulator reset). Two things of rviz's and tf's lose it otherwise, and
// the floor stays dark for a whole planning period (seen on a loaded CI machine, 27 Nov 2026):
//   - rviz resets every display at its first update after the jump (VisualizationManager::onUpdate,
//     every 33 ms at 30 frames/s), which clears the tf filter: a plan received in between is dropped.
//     retake() hands it back, to be filtered again.
//   - tf is cleared at the jump twice (tf2's listener at the first transform after it, rviz's reset
//     later): the transforms replayed just before the bag's first plan may be wiped after they came,
//     and a plan stamped before every transform tf now holds can never be transformed at its stamp.
//     olderThanTf() says so; the display then draws it with the newest transform (within a plan's
//     few tens of milliseconds the transform to the fixed frame barely moves).
// Only within ClockPolicy::kJumpGrace of a jump (or of ROS time starting); otherwise a plan waits
// for its transform as before, and a user's Reset clears the display.
#pragma once

#include <nav_msgs/Path.h>

#include "rviz_projector/core/clock_policy.h"

namespace rviz
{
class FrameManager;
}

namespace rviz_projector
{
class PathAfterJump
{
public:
  /// Every plan received, before the tf filter.
  void received(const nav_msgs::Path::ConstPtr& msg) { received_ = msg; }
  /// The plan received last (null: none).
  const nav_msgs::Path::ConstPtr& last() const { return received_; }
  /// At rviz's reset of the display: the last plan received, when the reset comes right after a
  /// backward jump (or the start) of ROS time and the plan belongs to the new timeline; else null.
  nav_msgs::Path::ConstPtr retake(const ClockPolicy& clock) const;
  /// Whether `msg` waits in the tf filter for a transform that will never come: right after a
  /// jump, stamped before the newest transform tf holds from its frame to the fixed frame, yet not
  /// transformable at its stamp (tf holds nothing that early any more).
  static bool olderThanTf(rviz::FrameManager& frames, const nav_msgs::Path& msg, const ClockPolicy& clock);
  void forget() { received_.reset(); }

private:
  nav_msgs::Path::ConstPtr received_;
};
}  // namespace rviz_projector
