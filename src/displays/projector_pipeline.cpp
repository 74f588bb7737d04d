#include "rviz_projector/displays/projector_pipeline.h"

#include "rviz_projector/displays/ros_clock.h"

#include <tf2_ros/buffer.h>
#include <utility>

namespace rviz_projector
{
LensEvent ProjectorPipeline::forgetLens()
{
  lens_.forget();
  LensEvent event{true, updateProjectorFrame()};
  return event;
}

LensEvent ProjectorPipeline::pollLens()
{
  LensEvent event = lens_.poll();
  if (event.frame)
  {
    event.frame = updateProjectorFrame();  // a new frame_id under a set Frame property changes nothing
  }
  return event;
}

bool ProjectorPipeline::setFrameProperty(const std::string& frame)
{
  frame_property_ = frame;
  return updateProjectorFrame();
}

bool ProjectorPipeline::updateProjectorFrame()
{
  std::string frame = frame_property_.empty() ? lens_.frameId() : frame_property_;
  if (frame == projector_frame_)
  {
    return false;
  }
  projector_frame_ = std::move(frame);
  motion_.clear();  // the poses it remembers are of another frame
  return true;
}

bool ProjectorPipeline::followClock(const ClockPolicy& clock)
{
  if (!epoch_.changed(clock))
  {
    return false;
  }
  // A bag loop: no pose, prediction or photon-delay measurement of before the jump is kept.
  motion_.clear();
  pose_.invalidate();
  return true;
}

void ProjectorPipeline::reset()
{
  motion_.clear();
  pose_.forget();
}

PoseStep ProjectorPipeline::followPose(const PoseInput& in, const ClockPolicy& clock)
{
  PoseStep step;
  if (!lens_.hasLens() || in.tf == nullptr || in.fixed_frame == nullptr)
  {
    pose_ok_ = false;
    if (pose_.shown())
    {
      step.transform_status_gone = true;
      pose_.forget();
    }
    return step;
  }
  const std::string& fixed_frame = *in.fixed_frame;
  if (fixed_frame != fixed_frame_)
  {
    fixed_frame_ = fixed_frame;
    motion_.clear();  // poses in another fixed frame
  }
  const double now = clock.rosNow();
  const ProjectorPoseFollower::Step followed =
      pose_.follow(*in.tf, fixed_frame, projector_frame_, now, in.tf_timeout);
  step.ok = followed.ok;
  step.transform_status_changed = followed.status_changed;  // a stale pose blanks as a missing one
  step.transform_problem = followed.problem;
  // Right after a backward jump: tf not there yet (rviz cleared its buffer) or still the pose of
  // before the jump (rviz has not cleared it yet): expected for a moment, a warning.
  const ProjectorPose& pose = pose_.pose();
  step.transform_problem_expected =
      !step.ok && clock.justStartedOrJumpedBack() &&
      (pose.state == ProjectorPose::NoTransform || (pose.state == ProjectorPose::Stale && pose.age < 0.0));
  if (step.transform_problem_expected)
  {
    step.transform_problem = kWaitingForTfAfterJump + step.transform_problem;
  }
  if (step.ok)
  {
    step.pose = motion_.follow(*in.tf, fixed_frame, pose_.pose(), in.motion, now, in.steady_now, in.period,
                               clock.rate(), step.motion);
  }
  pose_ok_ = step.ok;
  return step;
}

ros::Time ProjectorPipeline::imageStamp(const ros::Time& now) const
{
  const double pose_time = motion_.drawnPoseTime();
  return pose_time > 0.0 && pose_ok_ ? ros::Time(pose_time) : now;
}
}  // namespace rviz_projector
