// One part of ProjectorCameraDisplay: the projector's pose from tf, at the latest available time
// (a latched CameraInfo carries an old stamp; tf extrapolation errors must not blank the view), and
// whether that pose is too old to show (TF timeout: tf data older than it blanks the projector).
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include <boost/signals2/connection.hpp>

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
    NotFinite,    ///< the transform holds NaN/Inf
    Stale         ///< the newest tf of the chain is older than the TF timeout (the pose is filled in)
  };
  State state = NoFrame;
  std::string error;               ///< tf's message (NoTransform)
  RigidTransform optical_to_fixed; ///< valid when Ok
  double qx = 0, qy = 0, qz = 0, qw = 1;  ///< its rotation as tf gave it
  /// Seconds from the chain's stamp to `now` (Ok, Stale): tf's latest common time of the chain
  /// fixed frame -> frame, i.e. the newest data of its least recently updated moving link; 0 for a
  /// chain of static transforms only (stamp 0), which never goes stale.
  double age = 0;
  /// The chain's stamp, ROS time in seconds (0 for static transforms only).
  double stamp = 0;
};

/// Sets `pose.age` and Ok/Stale for ROS time `now`: older than `timeout`, or more than `timeout`
/// ahead of `now` (tf from before a backward jump of ROS time; age negative), is Stale.
void ageAt(ProjectorPose& pose, double now, double timeout);
/// The pose of `frame` in `fixed_frame` at the latest time tf has for the whole chain. `now` is
/// ros::Time::now() in seconds; with `timeout` > 0, a chain older than `timeout` seconds is Stale.
ProjectorPose lookupProjectorPose(tf2_ros::Buffer& tf, const std::string& fixed_frame, const std::string& frame,
                                  double now = 0.0, double timeout = 0.0);
/// The Transform status text of a pose that is not Ok (why the projector shows no scene).
std::string describeProblem(const ProjectorPose& pose, const std::string& fixed_frame, const std::string& frame,
                            double timeout);

/// The projector's pose frame after frame, and when the Transform status must change. A pose that
/// stays Ok (steady state, or the robot driving) builds no status text. It watches the tf buffer
/// for new transforms (tf2's transforms-changed signal): a frame with no new tf since the last
/// lookup and the same frames reuses that lookup (only its age is recomputed), so a still robot
/// costs no tf lookup (and no allocation) per frame.
class ProjectorPoseFollower
{
public:
  ProjectorPoseFollower();
  ~ProjectorPoseFollower();
  ProjectorPoseFollower(const ProjectorPoseFollower&) = delete;
  ProjectorPoseFollower& operator=(const ProjectorPoseFollower&) = delete;

  struct Step
  {
    bool ok = false;              ///< pose() is usable
    bool status_changed = false;  ///< show the Transform status anew: "OK" when ok, else `problem`
    std::string problem;          ///< why the projector shows no scene (when !ok)
  };
  /// Looks the pose up (lookupProjectorPose); a stale pose blanks the projector as a missing one.
  Step follow(tf2_ros::Buffer& tf, const std::string& fixed_frame, const std::string& frame, double now,
              double timeout);
  /// The Transform status is shown no more (rviz's Reset cleared it): the next follow() says it.
  void forget() { shown_ = -1; }
  /// ROS time jumped backwards: the next follow() looks the pose up anew (nothing of before is kept).
  void invalidate()
  {
    looked_up_ = false;
    pose_ = ProjectorPose();
  }
  /// Whether follow() has a Transform status shown.
  bool shown() const { return shown_ != -1; }
  /// The last pose looked up.
  const ProjectorPose& pose() const { return pose_; }
  /// Age of the last pose's tf, seconds (NaN when there was none).
  double tfAge() const;

private:
  /// Whether pose_ is still what tf would say for these frames (no new tf since it was looked up).
  bool reusable(const tf2_ros::Buffer& tf, const std::string& fixed_frame, const std::string& frame) const;

  ProjectorPose pose_;
  int shown_ = -1;  ///< the ProjectorPose::State whose status is shown, -1 for none
  /// Bumped by tf's thread at every transform added; shared so that a late signal finds it alive.
  std::shared_ptr<std::atomic<std::uint64_t>> tf_changes_;
  boost::signals2::connection watch_;
  const tf2_ros::Buffer* watched_ = nullptr;
  std::uint64_t looked_up_at_ = 0;  ///< tf_changes_ when pose_ was looked up
  bool looked_up_ = false;
  std::string fixed_frame_, frame_;  ///< the frames pose_ was looked up for
};
}  // namespace rviz_projector
