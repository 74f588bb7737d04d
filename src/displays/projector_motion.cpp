#include "rviz_projector/displays/projector_motion.h"

#include <cmath>
#include <cstdio>
#include <utility>

#include <tf2_ros/buffer.h>

#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
/// Odometry older than this (its stamp against the ROS clock) is not used: the tf poses are.
constexpr double kOdometryTimeout = 0.5;
/// A jump, gap or too fast motion stays in the status this long (a moment is too short to read).
constexpr double kAlarmHold = 2.0;
/// The Prediction line changes at most this often (it is text in the Displays panel).
constexpr double kLineInterval = 1.0;  // s; each change repaints rviz's property tree (costly on software rendering)

bool isAlarm(Prediction::State state)
{
  return state == Prediction::Jump || state == Prediction::Gap || state == Prediction::TooFast ||
         state == Prediction::Invalid;
}
}  // namespace

ProjectorMotion::ProjectorMotion()
{
  queue_.attach(nh_);
}

ProjectorMotion::~ProjectorMotion()
{
  odom_sub_.shutdown();
}

std::string ProjectorMotion::setOdometryTopic(const std::string& topic)
{
  odom_sub_.shutdown();
  odom_.reset();
  odom_topic_ = topic;
  if (topic.empty())
  {
    return std::string();
  }
  try
  {
    odom_sub_ = nh_.subscribe(topic, 1, &ProjectorMotion::onOdometry, this);
  }
  catch (const ros::Exception& e)
  {
    return e.what();
  }
  return std::string();
}

void ProjectorMotion::onOdometry(const nav_msgs::Odometry::ConstPtr& msg)
{
  odom_ = msg;
  odom_received_ = ros::Time::now().toSec();
}

void ProjectorMotion::clear()
{
  predictor_.clear();
  photon_.clear();
  last_ = Prediction();
  drawn_time_ = 0.0;
  lookup_steady_ = -1.0;
  alarm_until_ = -1.0;
}

bool ProjectorMotion::predictFromOdometry(tf2_ros::Buffer& tf, const std::string& fixed_frame, double ros_now,
                                          double target, double max_horizon, Prediction& out, std::string& why) const
{
  if (!odom_)
  {
    why = "no Odometry received on " + odom_topic_;
    return false;
  }
  const double stamp = odom_->header.stamp.isZero() ? odom_received_ : odom_->header.stamp.toSec();
  char text[96];
  if (ros_now - stamp > kOdometryTimeout)
  {
    std::snprintf(text, sizeof(text), "Odometry %.1f s old", ros_now - stamp);
    why = text;
    return false;
  }
  const auto& v = odom_->twist.twist;
  const PlanarTwist twist{v.linear.x, v.linear.y, v.angular.z};
  if (!std::isfinite(twist.vx) || !std::isfinite(twist.vy) || !std::isfinite(twist.wz))
  {
    why = "Odometry twist holds NaN/Inf";
    return false;
  }
  const std::string& base = odom_->child_frame_id.empty() ? std::string("base_link") : odom_->child_frame_id;
  geometry_msgs::TransformStamped t;
  try
  {
    t = tf.lookupTransform(fixed_frame, base, ros::Time(0));
  }
  catch (const tf2::TransformException& e)
  {
    why = "no tf of the Odometry's child frame [" + base + "]: " + e.what();
    return false;
  }
  out = predictor_.predictWithTwist(ros_now, target, max_horizon, toRigidTransform(t.transform), twist);
  return true;
}

ProjectorPose ProjectorMotion::follow(tf2_ros::Buffer& tf, const std::string& fixed_frame, const ProjectorPose& tf_pose,
                                      const MotionSettings& settings, double ros_now, double steady_now, double period,
                                      double rate, MotionReport& out)
{
  queue_.drain();  // only this part's own Odometry subscription
  lookup_steady_ = steady_now;
  std::string odometry_problem;
  if (tf_pose.stamp <= 0.0)
  {
    // Static transforms only: the projector does not move in the fixed frame.
    last_ = Prediction();
    last_.state = Prediction::Stopped;
    last_.pose = tf_pose.optical_to_fixed;
    drawn_time_ = 0.0;
    report(settings, odometry_problem, steady_now, out);
    return tf_pose;
  }
  predictor_.add(tf_pose.stamp, tf_pose.optical_to_fixed);
  // Measured in steady seconds, predicted for in ROS seconds (a bag at -r 0.5: half as far).
  const double ros_rate = std::isfinite(rate) && rate >= 0.0 ? rate : 1.0;
  last_target_ = ros_now + ros_rate * (photon_.expected(period) + settings.input_lag);
  if (!odom_topic_.empty() && predictFromOdometry(tf, fixed_frame, ros_now, last_target_, settings.max_prediction,
                                                  last_, odometry_problem))
  {
    odometry_problem.clear();
  }
  else
  {
    last_ = predictor_.predict(ros_now, last_target_, settings.max_prediction);
  }
  report(settings, odometry_problem, steady_now, out);
  if (!settings.enabled || !last_.extrapolated())
  {
    drawn_time_ = tf_pose.stamp;
    return tf_pose;
  }
  drawn_time_ = last_target_;
  ProjectorPose predicted = tf_pose;
  predicted.optical_to_fixed = last_.pose;
  const std::array<double, 4> q = last_.pose.quaternion();
  predicted.qx = q[0];
  predicted.qy = q[1];
  predicted.qz = q[2];
  predicted.qw = q[3];
  return predicted;
}

void ProjectorMotion::frameShown(double steady_shown, double period)
{
  if (lookup_steady_ >= 0.0)
  {
    photon_.frame(lookup_steady_, steady_shown, period);
  }
}

void ProjectorMotion::report(const MotionSettings& settings, const std::string& odometry_problem, double steady_now,
                             MotionReport& out)
{
  if (settings.enabled && isAlarm(last_.state))
  {
    alarm_ = "Prediction " + describePrediction(last_);
    alarm_until_ = steady_now + kAlarmHold;
  }
  MotionReport::Level level = MotionReport::Ok;
  std::string status = settings.enabled ? "On" : "Off";
  if (settings.enabled && steady_now < alarm_until_)
  {
    level = MotionReport::Warn;
    status = alarm_;
  }
  else if (settings.enabled && !odometry_problem.empty())
  {
    level = MotionReport::Warn;
    status = odometry_problem + ": the projector's tf poses are used instead";
  }
  out.status_changed = static_cast<int>(level) != level_shown_ || status != status_shown_;
  out.level = level;
  out.status = status;
  level_shown_ = static_cast<int>(level);
  status_shown_ = status;

  // The text is built only when it may be shown and its figures changed:
  // a still robot builds no text (and allocates nothing) per frame.
  out.line_changed = false;
  const std::array<long, 5> key{settings.enabled ? 1L : 0L, static_cast<long>(last_.state),
                                std::lround(last_.horizon * 1e3), std::lround(last_.speed * 100.0),
                                std::lround(last_.twist.wz * 573.0)};
  // A new state (or Enabled toggled) shows at once; changed figures of the same state once a second.
  const bool state_changed = key[0] != line_key_[0] || key[1] != line_key_[1];
  if (key != line_key_ && (state_changed || line_time_ < 0.0 || steady_now - line_time_ >= kLineInterval))
  {
    line_time_ = steady_now;
    line_key_ = key;
    std::string line = settings.enabled ? describePrediction(last_) : std::string("off (Enabled is unticked)");
    if (line != line_shown_)
    {
      out.line_changed = true;
      out.line = line;
      line_shown_ = std::move(line);
    }
  }
}
}  // namespace rviz_projector
