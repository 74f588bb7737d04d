// demo_navigation: a self-contained simulated robot for demonstrating rviz_projector without a robot
// or a navigation stack.
//
// A unicycle robot (base_link) drives in the map frame between a fixed cycle of goals, around a
// wet-floor-sign-sized box obstacle. About once a second it replans a curved, obstacle-avoiding path
// from its current pose to the goal and publishes it like move_base's global planner would: as a
// nav_msgs/Path in the odom frame, unevenly sampled with the occasional duplicate pose. The node also
// provides everything else the projector displays need: the map -> odom -> base_link tf chain, a
// static base_link -> projector_link -> projector_optical_frame mount, the projector's CameraInfo and
// a few helper markers (obstacle, robot footprint, current goal).
//
// Topics:   ~path_topic (/move_base/TrajectoryPlannerROS/global_plan) nav_msgs/Path, frame odom
//           /projector/camera_info   sensor_msgs/CameraInfo (latched)
//           /demo/obstacle           visualization_msgs/Marker (latched, 1 Hz)
//           /demo/robot_footprint    geometry_msgs/PolygonStamped (10 Hz)
//           /demo/odom               nav_msgs/Odometry (odom -> base_link, at ~tf_rate: the pose and
//                                    the unicycle's twist in base_link, for the Stop zone and motion
//                                    compensation)
//           /demo/goal               geometry_msgs/PoseStamped (latched, on every new goal)
//           ~status_topic (/move_base/status) actionlib_msgs/GoalStatusArray (10 Hz): the leg's goal
//           ACTIVE, then SUCCEEDED at the goal. With ~success_dwell and ~start_delay (s, default 0)
//           the robot stands still at a reached goal, then after a new goal became active, as a robot
//           that waits out a start warning would (demo.launch sets them for ProjectedPath's cues).
// Clock:    ROS time only (simulated under /use_sim_time: the robot then drives, stands and dwells
//           in step with /clock, at any rate). The simulation advances by the ROS time elapsed
//           between control ticks: never negative (a backward jump of ROS time -- a bag loop, a
//           simulator reset, the system clock stepped back -- passes no time, and the pauses go on
//           from where they were instead of waiting for the old time to come back), at most kMaxGap
//           per tick (a suspended machine, a clock skipping ahead). The pauses are durations counted
//           down by that elapsed time, not stamps to wait for. Under /use_sim_time the first goal
//           starts at the first tick of /clock (not stamped 0 before it).
// tf:       map -> odom (fixed offset), odom -> base_link (robot pose) at ~tf_rate;
//           static base_link -> projector_link -> projector_optical_frame.

#include <actionlib_msgs/GoalStatusArray.h>
#include <geometry_msgs/Point32.h>
#include <geometry_msgs/PolygonStamped.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/Marker.h>

#include "demo_world.h"
#include "ros_time_scheduler.h"

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace
{
using namespace rviz_projector_demo;

const char* const kMapFrame = "map";
const char* const kOdomFrame = "odom";
const char* const kBaseFrame = "base_link";
const char* const kProjectorFrame = "projector_link";
const char* const kProjectorOpticalFrame = "projector_optical_frame";

// ---------------------------------------------------------------------------------------------
// DemoNavigation: the ROS node gluing it together.
// ---------------------------------------------------------------------------------------------

template <typename T>
T positiveParam(const ros::NodeHandle& nh, const std::string& name, T fallback)
{
  T value = fallback;
  nh.param(name, value, fallback);
  if (!(value > T(0)))
  {
    ROS_WARN("~%s must be positive, using %g", name.c_str(), static_cast<double>(fallback));
    value = fallback;
  }
  return value;
}

class DemoNavigation
{
public:
  DemoNavigation(const ros::NodeHandle& nh, const ros::NodeHandle& pnh)
    : nh_(nh),
      pnh_(pnh),
      goals_{{0.0, 0.0}, {4.0, 0.0}, {4.0, 2.5}, {0.0, 2.5}},
      obstacle_{{2.0, 0.05}, 0.3, 0.3, 0.6},
      planner_(obstacle_, kRobotRadius, kClearanceMargin),
      sampler_(0.02, 0.09, 0.04, static_cast<unsigned>(pnh.param("seed", 42))),
      robot_({goals_.front().x, goals_.front().y, 0.0}, makeLimits(pnh))
  {
    // A fixed, slightly non-identity map -> odom offset like a localisation correction.
    tf2::Quaternion q;
    q.setRPY(0.0, 0.0, 0.03);
    map_to_odom_ = tf2::Transform(q, tf2::Vector3(0.10, -0.05, 0.0));

    const double replan_rate = positiveParam(pnh_, "replan_rate", 1.0);
    const double tf_rate = positiveParam(pnh_, "tf_rate", 50.0);
    const std::string path_topic =
        pnh_.param<std::string>("path_topic", "/move_base/TrajectoryPlannerROS/global_plan");

    path_pub_ = nh_.advertise<nav_msgs::Path>(path_topic, 1);
    goal_pub_ = nh_.advertise<geometry_msgs::PoseStamped>("/demo/goal", 1, true);
    obstacle_pub_ = nh_.advertise<visualization_msgs::Marker>("/demo/obstacle", 1, true);
    footprint_pub_ = nh_.advertise<geometry_msgs::PolygonStamped>("/demo/robot_footprint", 1);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/demo/odom", 10);
    status_pub_ = nh_.advertise<actionlib_msgs::GoalStatusArray>(
        pnh_.param<std::string>("status_topic", "/move_base/status"), 1);
    start_delay_ = std::max(0.0, pnh_.param("start_delay", 0.0));
    success_dwell_ = std::max(0.0, pnh_.param("success_dwell", 0.0));

    if (pnh_.param("publish_projector_tf", true))
    {
      publishProjectorTf();
    }
    if (pnh_.param("publish_camera_info", true))
    {
      camera_info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("/projector/camera_info", 1, true);
      camera_info_pub_.publish(makeCameraInfo());
    }

    ROS_INFO("demo_navigation: path on %s (frame %s), replan %.2f Hz, tf %.1f Hz, obstacle at "
             "(%.2f, %.2f), clearance %.3f m",
             path_pub_.getTopic().c_str(), kOdomFrame, replan_rate, tf_rate, obstacle_.center.x,
             obstacle_.center.y, planner_.clearance());

    if (ros::Time::isValid())
    {
      begin(ros::Time::now());
    }
    else
    {
      // Simulated time before the first /clock: nothing is stamped 0; the timers below first fire
      // on the clock's first ticks, and the first of them begins.
      ROS_INFO("demo_navigation: /use_sim_time is set and no /clock has come yet: the first goal "
               "starts with the clock");
    }

    scheduler_.add(1.0 / tf_rate, [this] { onControl(); });
    scheduler_.add(1.0 / replan_rate, [this] { onReplan(); });
    scheduler_.add(0.1, [this] { onFootprint(); });
    scheduler_.add(1.0, [this] { onObstacle(); });
    scheduler_.start(nh_);
  }

private:
  static constexpr double kRobotRadius = 0.3;
  static constexpr double kClearanceMargin = 0.1;
  static constexpr double kGoalTolerance = 0.05;
  static constexpr double kMaxStep = 0.02;  // s of ROS time per integration step of the robot
  static constexpr double kMaxGap = 1.0;    // s; larger gaps between ticks (suspended) are clipped
  static constexpr int kFootprintPoints = 24;

  static RobotLimits makeLimits(const ros::NodeHandle& pnh)
  {
    RobotLimits limits;
    limits.max_speed = positiveParam(pnh, "max_speed", limits.max_speed);
    limits.max_turn_rate = positiveParam(pnh, "max_turn_rate", limits.max_turn_rate);
    limits.lookahead = positiveParam(pnh, "lookahead", limits.lookahead);
    return limits;
  }

  // --- timer callbacks ---------------------------------------------------------------------

  void onControl()
  {
    const ros::Time now = ros::Time::now();
    if (now.isZero())
    {
      return;  // simulated time, no /clock yet
    }
    if (!started_)
    {
      begin(now);
      return;
    }
    advance(elapsedSince(now), now);
    broadcastRobotTf(now);
  }

  // The first leg, at the first valid ROS time.
  void begin(const ros::Time& now)
  {
    started_ = true;
    last_tick_ = now;
    publishObstacle(now);
    broadcastRobotTf(now);
    startLeg(1, now);
  }

  // ROS time since the previous control tick, in [0, kMaxGap] (see "Clock" at the top).
  double elapsedSince(const ros::Time& now)
  {
    const double dt = (now - last_tick_).toSec();
    last_tick_ = now;
    if (dt < 0.0)
    {
      ROS_WARN("demo_navigation: ROS time jumped back by %.3f s: no time passes for the robot, its "
               "pause (%.2f s left) and motion go on from here",
               -dt, hold_left_);
      return 0.0;
    }
    if (dt > kMaxGap)
    {
      ROS_WARN_THROTTLE(10.0, "demo_navigation: %.3f s of ROS time since the last control tick: "
                        "the robot moves %.1f s of it",
                        dt, kMaxGap);
      return kMaxGap;
    }
    return dt;
  }

  // Moves the simulation on by dt s of ROS time: the pause at a reached goal, then the start
  // delay, then driving (in steps of kMaxStep, stopping at the goal). A leg's change is stamped
  // with this tick's time; what is left of the tick after it is not used.
  void advance(double dt, const ros::Time& now)
  {
    leg_time_ += dt;
    if (dwelling_)
    {
      hold_left_ -= dt;
      if (hold_left_ > 0.0)
      {
        return;
      }
      dwelling_ = false;
      startLeg((goal_index_ + 1) % goals_.size(), now);
      return;
    }
    const double held = std::min(dt, hold_left_);  // standing still: start delay
    hold_left_ -= held;
    dt -= held;
    while (dt > 0.0 && !atGoal())
    {
      const double step = std::min(dt, kMaxStep);
      robot_.step(step);
      dt -= step;
    }
    if (atGoal())
    {
      reachGoal(now);
    }
  }

  bool atGoal() const
  {
    return distance(robot_.pose().position(), goals_[goal_index_]) < kGoalTolerance;
  }

  void reachGoal(const ros::Time& now)
  {
    const Vec2 goal = goals_[goal_index_];
    ROS_INFO("demo_navigation: reached goal %zu (%.2f, %.2f) after %.1f s", goal_index_, goal.x,
             goal.y, leg_time_);
    goal_status_ = actionlib_msgs::GoalStatus::SUCCEEDED;
    publishStatus(now);
    if (success_dwell_ > 0.0)
    {
      dwelling_ = true;
      hold_left_ = success_dwell_;
      return;
    }
    startLeg((goal_index_ + 1) % goals_.size(), now);
  }

  void publishStatus(const ros::Time& now)
  {
    actionlib_msgs::GoalStatusArray status;
    status.header.stamp = now;
    status.status_list.resize(1);
    status.status_list[0].goal_id.id = "demo_goal_" + std::to_string(goal_count_);
    status.status_list[0].goal_id.stamp = leg_start_;
    status.status_list[0].status = goal_status_;
    status_pub_.publish(status);
  }

  void onReplan()
  {
    if (!started_)
    {
      return;
    }
    // Re-broadcast the (unchanged) robot pose with the plan's stamp first, so consumers can
    // transform the plan at its own stamp right away instead of waiting for the next tf tick.
    const ros::Time now = ros::Time::now();
    broadcastRobotTf(now);
    replan(now);
  }

  void onFootprint()
  {
    geometry_msgs::PolygonStamped footprint;
    footprint.header.frame_id = kBaseFrame;
    footprint.header.stamp = ros::Time::now();
    for (int i = 0; i < kFootprintPoints; ++i)
    {
      const double angle = 2.0 * kPi * i / kFootprintPoints;
      geometry_msgs::Point32 p;
      p.x = static_cast<float>(kRobotRadius * std::cos(angle));
      p.y = static_cast<float>(kRobotRadius * std::sin(angle));
      footprint.polygon.points.push_back(p);
    }
    footprint_pub_.publish(footprint);
    if (started_)
    {
      publishStatus(footprint.header.stamp);
    }
  }

  void onObstacle()
  {
    if (started_)
    {
      publishObstacle(ros::Time::now());
    }
  }

  // --- navigation ----------------------------------------------------------------------------

  void startLeg(std::size_t goal_index, const ros::Time& stamp)
  {
    const Vec2 from = robot_.pose().position();
    goal_index_ = goal_index;
    leg_start_ = stamp;
    leg_time_ = 0.0;
    ++goal_count_;
    goal_status_ = actionlib_msgs::GoalStatus::ACTIVE;
    hold_left_ = start_delay_;
    publishStatus(stamp);
    const Vec2 goal = goals_[goal_index_];
    ROS_INFO("demo_navigation: new goal %zu (%.2f, %.2f), %.2f m from the robot at (%.2f, %.2f)",
             goal_index_, goal.x, goal.y, distance(from, goal), from.x, from.y);

    // The goal's orientation is the direction of travel from the previous goal.
    const Vec2 previous = goals_[(goal_index_ + goals_.size() - 1) % goals_.size()];
    geometry_msgs::PoseStamped goal_msg;
    goal_msg.header.frame_id = kMapFrame;
    goal_msg.header.stamp = stamp;
    tf2::toMsg(toTransform({goal.x, goal.y, std::atan2(goal.y - previous.y, goal.x - previous.x)}),
               goal_msg.pose);
    goal_pub_.publish(goal_msg);

    replan(stamp);
  }

  // Plans in the map frame from the current robot pose, hands the plan to the robot and publishes
  // it expressed in odom, as move_base would.
  void replan(const ros::Time& stamp)
  {
    const std::vector<Pose2D> plan =
        sampler_.sample(planner_.plan(robot_.pose().position(), goals_[goal_index_]));
    robot_.setPlan(plan);

    const tf2::Transform odom_from_map = map_to_odom_.inverse();
    nav_msgs::Path path;
    path.header.frame_id = kOdomFrame;
    path.header.stamp = stamp;
    path.poses.reserve(plan.size());
    for (const Pose2D& pose : plan)
    {
      geometry_msgs::PoseStamped pose_msg;
      pose_msg.header = path.header;
      tf2::toMsg(odom_from_map * toTransform(pose), pose_msg.pose);
      path.poses.push_back(pose_msg);
    }
    path_pub_.publish(path);
  }

  // --- tf and fixed messages -------------------------------------------------------------------

  void broadcastRobotTf(const ros::Time& stamp)
  {
    // The robot lives in map; odom -> base_link = inverse(map -> odom) * map -> base_link.
    const tf2::Transform odom_to_base = map_to_odom_.inverse() * toTransform(robot_.pose());
    std::vector<geometry_msgs::TransformStamped> transforms(2);
    transforms[0].header.stamp = stamp;
    transforms[0].header.frame_id = kMapFrame;
    transforms[0].child_frame_id = kOdomFrame;
    transforms[0].transform = tf2::toMsg(map_to_odom_);
    transforms[1].header.stamp = stamp;
    transforms[1].header.frame_id = kOdomFrame;
    transforms[1].child_frame_id = kBaseFrame;
    transforms[1].transform = tf2::toMsg(odom_to_base);
    tf_broadcaster_.sendTransform(transforms);

    nav_msgs::Odometry odom;
    odom.header = transforms[1].header;
    odom.child_frame_id = kBaseFrame;
    tf2::toMsg(odom_to_base, odom.pose.pose);
    odom.twist.twist.linear.x = robot_.speed();
    odom.twist.twist.angular.z = robot_.turnRate();
    odom_pub_.publish(odom);
  }

  void publishProjectorTf()
  {
    const double height = pnh_.param("projector_height", 1.2);
    const double x = pnh_.param("projector_x", 0.15);
    const double aim_distance = positiveParam(pnh_, "projector_aim_distance", 1.0);
    // Positive pitch about +y tilts the x axis down (REP-103), so the optical axis (projector
    // x = optical z) hits the floor aim_distance ahead of the projector.
    const double pitch = std::atan2(height, aim_distance);

    const ros::Time now = ros::Time::now();
    std::vector<geometry_msgs::TransformStamped> transforms(2);
    tf2::Quaternion mount;
    mount.setRPY(0.0, pitch, 0.0);
    transforms[0].header.stamp = now;
    transforms[0].header.frame_id = kBaseFrame;
    transforms[0].child_frame_id = kProjectorFrame;
    transforms[0].transform = tf2::toMsg(tf2::Transform(mount, tf2::Vector3(x, 0.0, height)));

    // Body (x forward, y left, z up) -> optical (z forward, x right, y down).
    transforms[1].header.stamp = now;
    transforms[1].header.frame_id = kProjectorFrame;
    transforms[1].child_frame_id = kProjectorOpticalFrame;
    transforms[1].transform.rotation.x = -0.5;
    transforms[1].transform.rotation.y = 0.5;
    transforms[1].transform.rotation.z = -0.5;
    transforms[1].transform.rotation.w = 0.5;
    static_broadcaster_.sendTransform(transforms);

    ROS_INFO("demo_navigation: projector at x=%.2f z=%.2f m, pitched down %.1f deg", x, height,
             pitch * 180.0 / kPi);
  }

  static sensor_msgs::CameraInfo makeCameraInfo()
  {
    constexpr double fx = 1300.0;
    constexpr double fy = 1300.0;
    constexpr double cx = 639.5;
    constexpr double cy = 399.5;
    sensor_msgs::CameraInfo info;
    info.header.frame_id = kProjectorOpticalFrame;
    info.header.stamp = ros::Time::now();
    info.width = 1280;
    info.height = 800;
    info.distortion_model = "plumb_bob";
    info.D.assign(5, 0.0);
    info.K = {fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0};
    info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    info.P = {fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0};
    return info;
  }

  void publishObstacle(const ros::Time& stamp)
  {
    visualization_msgs::Marker marker;
    marker.header.frame_id = kMapFrame;
    marker.header.stamp = stamp;
    marker.ns = "demo_obstacle";
    marker.id = 0;
    marker.type = visualization_msgs::Marker::CUBE;
    marker.action = visualization_msgs::Marker::ADD;
    marker.pose.position.x = obstacle_.center.x;
    marker.pose.position.y = obstacle_.center.y;
    marker.pose.position.z = 0.5 * obstacle_.height;
    marker.pose.orientation.w = 1.0;
    marker.scale.x = obstacle_.size_x;
    marker.scale.y = obstacle_.size_y;
    marker.scale.z = obstacle_.height;
    marker.color.r = 1.0f;  // wet-floor-sign yellow-orange
    marker.color.g = 0.75f;
    marker.color.b = 0.0f;
    marker.color.a = 1.0f;
    obstacle_pub_.publish(marker);
  }

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;

  const std::vector<Vec2> goals_;
  const BoxObstacle obstacle_;
  DetourPlanner planner_;
  UnevenSampler sampler_;
  SimulatedRobot robot_;
  tf2::Transform map_to_odom_;
  std::size_t goal_index_{0};
  ros::Time leg_start_;        // stamp of the current goal
  double leg_time_{0.0};       // s of ROS time since then (backward jumps not counted)
  bool started_{false};        // the first goal has started (ROS time was valid)
  ros::Time last_tick_;        // ROS time of the previous control tick

  ros::Publisher path_pub_;
  ros::Publisher goal_pub_;
  ros::Publisher status_pub_;
  double start_delay_{0.0};
  double success_dwell_{0.0};
  double hold_left_{0.0};      // s of ROS time the robot still stands (start delay or dwell)
  bool dwelling_{false};       // standing at a reached goal
  unsigned goal_count_{0};
  std::uint8_t goal_status_{actionlib_msgs::GoalStatus::ACTIVE};
  ros::Publisher obstacle_pub_;
  ros::Publisher footprint_pub_;
  ros::Publisher odom_pub_;
  ros::Publisher camera_info_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;

  RosTimeScheduler scheduler_{"demo_navigation"};  // control, replan, footprint, obstacle (ROS time)
};

}  // namespace

int main(int argc, char** argv)
{
  // roscpp's default SIGINT handler calls ros::shutdown(), which makes ros::spin() return.
  ros::init(argc, argv, "demo_navigation");
  DemoNavigation node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
