#include "rviz_projector/displays/projector_pose.h"

#include <cmath>

#include <tf2_ros/buffer.h>

namespace rviz_projector
{
ProjectorPose lookupProjectorPose(tf2_ros::Buffer& tf, const std::string& fixed_frame, const std::string& frame)
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
  pose.state = ProjectorPose::Ok;
  pose.qx = q.x;
  pose.qy = q.y;
  pose.qz = q.z;
  pose.qw = q.w;
  pose.optical_to_fixed = RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, Vec3{p.x, p.y, p.z});
  return pose;
}
}  // namespace rviz_projector
