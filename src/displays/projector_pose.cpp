#include "rviz_projector/displays/projector_pose.h"

#include <cmath>
#include <cstdio>

#include <tf2_ros/buffer.h>
#include <utility>

#include "rviz_projector/core/data_age.h"

namespace rviz_projector
{
void ageAt(ProjectorPose& pose, double now, double timeout)
{
  if (isFromTheFuture(pose.stamp, now, timeout))
  {
    pose.age = now - pose.stamp;  // negative: ahead of ROS time
    pose.state = ProjectorPose::Stale;
    return;
  }
  pose.age = dataAge(pose.stamp, now);
  pose.state = isStale(pose.age, timeout) ? ProjectorPose::Stale : ProjectorPose::Ok;
}

ProjectorPose lookupProjectorPose(tf2_ros::Buffer& tf, const std::string& fixed_frame, const std::string& frame,
                                  double now, double timeout)
{
  ProjectorPose pose;
  if (frame.empty())
  {
    pose.state = ProjectorPose::NoFrame;
    return pose;
  }
  geometry_msgs::TransformStamped t;
  try
  {
    t = tf.lookupTransform(fixed_frame, frame, ros::Time(0));
  }
  catch (const tf2::TransformException& e)
  {
    pose.state = ProjectorPose::NoTransform;
    pose.error = e.what();
    return pose;
  }
  const auto& q = t.transform.rotation;
  const auto& p = t.transform.translation;
  for (double v : {q.x, q.y, q.z, q.w, p.x, p.y, p.z})
  {
    if (!std::isfinite(v))
    {
      pose.state = ProjectorPose::NotFinite;
      return pose;
    }
  }
  // With ros::Time(0), tf stamps the result with the chain's latest common time (0 when all static).
  pose.stamp = t.header.stamp.toSec();
  ageAt(pose, now, timeout);
  pose.qx = q.x;
  pose.qy = q.y;
  pose.qz = q.z;
  pose.qw = q.w;
  pose.optical_to_fixed = RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, Vec3{p.x, p.y, p.z});
  return pose;
}

std::string describeProblem(const ProjectorPose& pose, const std::string& fixed_frame, const std::string& frame,
                            double timeout)
{
  switch (pose.state)
  {
    case ProjectorPose::NoFrame:
      return "No projector frame: the CameraInfo header has no frame_id and the Frame property is empty";
    case ProjectorPose::NoTransform:
      return "No transform from projector frame [" + frame + "] to fixed frame [" + fixed_frame + "]: " + pose.error;
    case ProjectorPose::NotFinite:
      return "Transform of [" + frame + "] contains NaN/Inf";
    case ProjectorPose::Stale:
    {
      // Tenths of a second: the text (and the status) changes at most 10 times a second.
      char text[96];
      if (pose.age < 0.0)
      {
        std::snprintf(text, sizeof(text), "%.1f s ahead of ROS time (TF timeout %g s; did time jump back?)", -pose.age,
                      timeout);
      }
      else
      {
        std::snprintf(text, sizeof(text), "%.1f s old (TF timeout %g s)", pose.age, timeout);
      }
      return "tf of '" + frame + "' in '" + fixed_frame + "' is " + text + ": projector blanked";
    }
    case ProjectorPose::Ok:
      break;
  }
  return std::string();
}

ProjectorPoseFollower::ProjectorPoseFollower() : tf_changes_(std::make_shared<std::atomic<std::uint64_t>>(0))
{
}

ProjectorPoseFollower::~ProjectorPoseFollower()
{
  watch_.disconnect();
}

bool ProjectorPoseFollower::reusable(const tf2_ros::Buffer& tf, const std::string& fixed_frame,
                                     const std::string& frame) const
{
  return looked_up_ && watched_ == &tf && looked_up_at_ == tf_changes_->load() && fixed_frame == fixed_frame_ &&
         frame == frame_ && (pose_.state == ProjectorPose::Ok || pose_.state == ProjectorPose::Stale);
}

ProjectorPoseFollower::Step ProjectorPoseFollower::follow(tf2_ros::Buffer& tf, const std::string& fixed_frame,
                                                          const std::string& frame, double now, double timeout)
{
  if (watched_ != &tf || !watch_.connected())  // a new buffer (possibly at a dead one's address)
  {
    watch_.disconnect();
    std::weak_ptr<std::atomic<std::uint64_t>> changes = tf_changes_;
    watch_ = tf._addTransformsChangedListener([changes] {
      if (auto c = changes.lock())
      {
        ++*c;
      }
    });
    watched_ = &tf;
    looked_up_ = false;
  }
  if (reusable(tf, fixed_frame, frame))
  {
    // No new tf: the same pose, only older.
    ageAt(pose_, now, timeout);
  }
  else
  {
    looked_up_at_ = tf_changes_->load();  // before the lookup: a tf arriving during it is looked up next frame
    pose_ = lookupProjectorPose(tf, fixed_frame, frame, now, timeout);
    looked_up_ = true;
    if (fixed_frame != fixed_frame_ || frame != frame_)
    {
      fixed_frame_ = fixed_frame;
      frame_ = frame;
    }
  }
  Step step;
  step.ok = pose_.state == ProjectorPose::Ok;
  step.status_changed = !step.ok || shown_ != ProjectorPose::Ok;
  if (!step.ok)
  {
    step.problem = describeProblem(pose_, fixed_frame, frame, timeout);
  }
  shown_ = pose_.state;
  return step;
}

double ProjectorPoseFollower::tfAge() const
{
  return pose_.state == ProjectorPose::Ok || pose_.state == ProjectorPose::Stale ? pose_.age : std::nan("");
}
}  // namespace rviz_projector
