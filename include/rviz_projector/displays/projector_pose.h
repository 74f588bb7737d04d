// One part of ProjectorCameraDisplay: the projector's pose from tf, at the latest available time
// (a latched CameraInfo carries an old stamp; tf extrapolation errors must not blank the view).
#pragma once

#include <string>

#include "rviz_projector/core/rigid_transform.h"

namespace tf2_ros
{
class Buffer;
}

namespace rviz_projector
{
struct ProjectorPose
{
  enum State
  {
    Ok,
    NoFrame,      ///< no frame_id in the CameraInfo and the Frame property is empty
    NoTransform,  ///< tf cannot transform the frame into the fixed frame
    NotFinite     ///< the transform holds NaN/Inf
  };
  State state = NoFrame;
  std::string error;               ///< tf's message (NoTransform)
  RigidTransform optical_to_fixed; ///< valid when Ok
  double qx = 0, qy = 0, qz = 0, qw = 1;  ///< its rotation as tf gave it
};

ProjectorPose lookupProjectorPose(tf2_ros::Buffer& tf, const std::string& fixed_frame, const std::string& frame);
}  // namespace rviz_projector
