// The projector's mount pose as projector.launch takes it, and the optical frame it implies.
//
// Convention (launch/projector.launch): parent_frame -> projector body frame by x y z and fixed-axis
// roll, pitch, yaw (R = Rz(yaw) * Ry(pitch) * Rx(roll), REP-103, positive pitch tilts the beam
// down), then body -> optical frame by the standard rotation (z along the beam, x right, y down):
// quaternion (x, y, z, w) = (-0.5, 0.5, -0.5, 0.5).
#pragma once

#include "rviz_projector/core/rigid_transform.h"

namespace rviz_projector
{
struct ProjectorMount
{
  double x = 0.0;  ///< metres, in the parent frame
  double y = 0.0;
  double z = 0.0;
  double roll = 0.0;   ///< radians
  double pitch = 0.0;  ///< radians, positive: beam down
  double yaw = 0.0;    ///< radians, positive: beam turned left
};

/// Pose of the optical frame in the parent frame (p_parent = T.apply(p_optical)).
RigidTransform opticalPoseOfMount(const ProjectorMount& mount);

/// The mount whose optical frame has this pose (inverse of opticalPoseOfMount; roll and yaw in
/// (-pi, pi], pitch in [-pi/2, pi/2]).
ProjectorMount mountOfOpticalPose(const RigidTransform& parent_T_optical);
}  // namespace rviz_projector
