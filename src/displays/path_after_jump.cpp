#include "rviz_projector/displays/path_after_jump.h"

#include <string>

#include <rviz/frame_manager.h>
#include <tf2/exceptions.h>
#include <tf2_ros/buffer.h>

namespace rviz_projector
{
nav_msgs::Path::ConstPtr PathAfterJump::retake(const ClockPolicy& clock) const
{
  if (!received_ || !clock.justStartedOrJumpedBack() ||
      !ClockPolicy::inCurrentTimeline(received_->header.stamp.toSec(), clock.rosNow()))
  {
    return nullptr;
  }
  return received_;
}

bool PathAfterJump::olderThanTf(rviz::FrameManager& frames, const nav_msgs::Path& msg, const ClockPolicy& clock)
{
  if (!clock.justStartedOrJumpedBack() || msg.header.stamp.isZero() ||
      !ClockPolicy::inCurrentTimeline(msg.header.stamp.toSec(), clock.rosNow()))
  {
    return false;
  }
  std::string error;
  if (!frames.transformHasProblems(msg.header.frame_id, msg.header.stamp, error))
  {
    return false;  // transformable: the tf filter lets it through
  }
  try
  {
    // The newest time tf can transform the whole chain at; tf interpolates between its samples, so
    // a stamp before it that still fails lies before the oldest sample of some link.
    const ros::Time newest =
        frames.getTF2BufferPtr()->lookupTransform(frames.getFixedFrame(), msg.header.frame_id, ros::Time()).header.stamp;
    return !newest.isZero() && msg.header.stamp < newest;
  }
  catch (const tf2::TransformException&)
  {
    return false;  // no transform at all (yet): wait as usual
  }
}
}  // namespace rviz_projector
