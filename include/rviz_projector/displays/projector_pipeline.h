// The ProjectorCamera's per-frame pipeline, without rviz (issue 23): from the projector's lens
// (CameraInfo), its frame, the fixed frame, the clock and tf to the pose a frame is drawn from and
// what the display must report. Every event is explicit (a lens or frame_id change, a new Frame
// property, a backward jump of ROS time, rviz's Reset), and so is every reset it causes; nothing is
// drawn or shown here: the display turns the results into OGRE calls and statuses.
//
//   ProjectorLensSource      CameraInfo (private queue) -> PinholeModel; only changed values are events
//   ProjectorPoseFollower    the projector's pose from tf, TF timeout, poses "ahead of ROS time"
//   ProjectorMotion          motion compensation (MotionPredictor, PhotonDelay: core)
//   ClockPolicy (core)       ROS time, its rate, backward jumps (RosClock::shared() in rviz)
#pragma once

#include <string>

#include <ros/time.h>

#include "rviz_projector/core/clock_policy.h"
#include "rviz_projector/displays/projector_lens_source.h"
#include "rviz_projector/displays/projector_motion.h"
#include "rviz_projector/displays/projector_pose.h"

namespace tf2_ros
{
class Buffer;
}

namespace rviz_projector
{
/// What one frame's pose is made from, besides the pipeline's own state.
struct PoseInput
{
  tf2_ros::Buffer* tf = nullptr;
  const std::string* fixed_frame = nullptr;  ///< not copied: no allocation per frame
  MotionSettings motion;
  double tf_timeout = 1.0;   ///< s (0: never stale)
  double steady_now = 0.0;   ///< s, monotonic: the lookup time the photon delay is measured from
  double period = 0.0;       ///< s, the frame period aimed at
};

/// What one frame's pose step did, for the display to draw and show.
struct PoseStep
{
  bool ok = false;                    ///< a fresh pose: draw the scene from `pose`
  ProjectorPose pose;                 ///< the pose to render from (motion compensation applied)
  bool transform_status_changed = false;  ///< show "Transform" anew: OK, or `transform_problem`
  std::string transform_problem;
  /// The problem is tf still missing within ClockPolicy::kJumpGrace after a backward jump of ROS
  /// time (rviz cleared its buffer; the bag plays it again): a warning, not an error.
  bool transform_problem_expected = false;
  bool transform_status_gone = false; ///< no lens any more: the Transform status goes
  MotionReport motion;                ///< the Motion compensation status / Prediction line (when ok)
};

class ProjectorPipeline
{
public:
  // --- inputs and their events ---
  /// Subscribes the lens to a CameraInfo topic; an error text or empty.
  std::string subscribeLens(const std::string& topic) { return lens_.subscribe(topic); }
  void unsubscribeLens() { lens_.unsubscribe(); }
  /// The CameraInfo topic changed: the lens and its frame_id are forgotten.
  LensEvent forgetLens();
  /// Handles the CameraInfo messages that arrived: what they changed. A new projector frame (the
  /// Frame property empty and a new frame_id) restarts the motion history; a new lens does not.
  LensEvent pollLens();
  /// The Frame property (empty: the CameraInfo's frame_id). True when the projector frame changed
  /// (the motion history restarted).
  bool setFrameProperty(const std::string& frame);
  /// The Motion compensation's Odometry topic (empty: none); an error text or empty.
  std::string setOdometryTopic(const std::string& topic) { return motion_.setOdometryTopic(topic); }
  /// The clock of this frame. True when ROS time jumped backwards since the last call: the motion
  /// history, photon-delay measurements and the cached tf lookup are gone.
  bool followClock(const ClockPolicy& clock);
  /// rviz's Reset, or the display enabled again: the motion history is gone and the Transform
  /// status counts as not shown.
  void reset();

  // --- one frame ---
  /// The pose to draw this frame from (needs a lens). `clock` is this frame's reading.
  PoseStep followPose(const PoseInput& in, const ClockPolicy& clock);
  /// The frame drawn from the last followPose() was handed to the screen at `steady_shown`.
  void frameShown(double steady_shown, double period) { motion_.frameShown(steady_shown, period); }
  /// The stamp of an image of the last frame: the time of the pose it was drawn from (the
  /// prediction's target when compensation predicted, the tf pose's stamp otherwise), `now` when
  /// that pose is static or there was none.
  ros::Time imageStamp(const ros::Time& now) const;

  // --- reads ---
  bool hasLens() const { return lens_.hasLens(); }
  const PinholeModel& lens() const { return lens_.lens(); }
  const ProjectorLensSource& lensSource() const { return lens_; }
  const ProjectorPoseFollower& poseFollower() const { return pose_; }
  const ProjectorMotion& motion() const { return motion_; }
  /// The Frame property, or the CameraInfo's frame_id when it is empty.
  const std::string& projectorFrame() const { return projector_frame_; }
  /// Whether the last followPose() gave a fresh pose.
  bool poseOk() const { return pose_ok_; }

private:
  /// projector_frame_ from the Frame property and the lens's frame_id; true when it changed.
  bool updateProjectorFrame();

  ProjectorLensSource lens_;
  ProjectorPoseFollower pose_;
  ProjectorMotion motion_;
  EpochWatch epoch_;
  std::string frame_property_;
  std::string projector_frame_;
  std::string fixed_frame_;  ///< of the motion history
  bool pose_ok_ = false;
};
}  // namespace rviz_projector
