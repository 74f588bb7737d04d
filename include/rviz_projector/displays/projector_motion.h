// One part of ProjectorCameraDisplay: motion compensation (issue 14). Frame by frame it is given
// the projector's pose from tf and returns the pose to render from: the pose predicted (core
// MotionPredictor) for the middle of the frame's time on the floor,
//     t_photon = now + render delay + hold / 2 (PhotonDelay, measured here) + projector input lag,
// from the projector's recent tf poses, or from the twist of an Odometry topic (subscribed on a
// callback queue of its own, drained at each frame: never rviz's global queue). It returns what
// the Motion compensation status and the read-only Prediction line must say; the display shows it.
#pragma once

#include <array>
#include <string>

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>

#include "rviz_projector/displays/private_callback_queue.h"

#include "rviz_projector/core/motion_predictor.h"
#include "rviz_projector/core/photon_delay.h"
#include "rviz_projector/displays/projector_pose.h"

namespace tf2_ros
{
class Buffer;
}

namespace rviz_projector
{
struct MotionSettings
{
  bool enabled = true;
  double input_lag = 0.0;       ///< s
  double max_prediction = 0.15; ///< s
};

/// What the display shows of motion compensation after a frame.
struct MotionReport
{
  enum Level
  {
    Ok,
    Warn
  };
  bool status_changed = false;  ///< show `level` / `status` as the "Motion compensation" status
  Level level = Ok;
  std::string status;
  bool line_changed = false;    ///< show `line` in the read-only Prediction property
  std::string line;
};

class ProjectorMotion
{
public:
  ProjectorMotion();
  ~ProjectorMotion();
  ProjectorMotion(const ProjectorMotion&) = delete;
  ProjectorMotion& operator=(const ProjectorMotion&) = delete;

  /// Subscribes to an Odometry topic (empty: none, the tf poses are used); an error text or empty.
  std::string setOdometryTopic(const std::string& topic);
  /// Forgets the poses and measurements (frame changed, display reset or re-enabled).
  void clear();

  /// The pose to draw a frame from. `tf_pose` is the projector's pose from tf (state Ok);
  /// `ros_now` the ROS time and `steady_now` a monotonic time (s) at the lookup; `period` the
  /// frame period the projector aims at. Fills `report` with what changed for the display.
  /// `rate` is ROS seconds per steady second (ClockPolicy::rate()): the photon delay and the input
  /// lag are measured in steady seconds and predicted for in ROS seconds.
  ProjectorPose follow(tf2_ros::Buffer& tf, const std::string& fixed_frame, const ProjectorPose& tf_pose,
                       const MotionSettings& settings, double ros_now, double steady_now, double period, double rate,
                       MotionReport& report);
  /// The frame drawn from the last follow() was handed to the screen at `steady_shown`.
  void frameShown(double steady_shown, double period);

  /// The last prediction (for health() and tests): its state, horizon, twist.
  const Prediction& lastPrediction() const { return last_; }
  /// The ROS time the last pose was predicted for (t_photon).
  double lastTarget() const { return last_target_; }
  /// The ROS time of the pose the last frame was drawn from: lastTarget() when it predicted, the
  /// newest tf pose's stamp otherwise (0 for a static pose).
  double drawnPoseTime() const { return drawn_time_; }
  /// Expected seconds from lookup to the middle of a frame's time on screen (without input lag).
  double photonDelay(double period) const { return photon_.expected(period); }

private:
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  /// The prediction from the odometry twist, or false when there is none usable (`why` says why).
  bool predictFromOdometry(tf2_ros::Buffer& tf, const std::string& fixed_frame, double ros_now, double target,
                           double max_horizon, Prediction& out, std::string& why) const;
  void report(const MotionSettings& settings, const std::string& odometry_problem, double steady_now,
              MotionReport& out);

  MotionPredictor predictor_;
  PhotonDelay photon_;
  Prediction last_;
  double last_target_ = 0.0;
  double drawn_time_ = 0.0;
  double lookup_steady_ = -1.0;  ///< when the last follow() looked up (frameShown pairs it)
  // Odometry: declared before the subscriber, the queue outlives the subscription.
  PrivateCallbackQueue queue_;  ///< drained by the projector's frame clock (paused while disabled)
  ros::NodeHandle nh_;
  ros::Subscriber odom_sub_;
  std::string odom_topic_;
  nav_msgs::Odometry::ConstPtr odom_;
  double odom_received_ = -1.0;  ///< ROS time it arrived
  // What the display shows, to change it only when it changes.
  std::string status_shown_;
  int level_shown_ = -1;
  std::string line_shown_;
  double line_time_ = -1.0;      ///< steady time the line was last built
  std::array<long, 5> line_key_{};  ///< the figures (rounded as shown) the line was built from
  double alarm_until_ = -1.0;    ///< a jump/gap/too-fast warning stays up until this steady time
  std::string alarm_;
};
}  // namespace rviz_projector
