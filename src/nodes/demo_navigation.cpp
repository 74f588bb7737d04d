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
//           /demo/goal               geometry_msgs/PoseStamped (latched, on every new goal)
//           ~status_topic (/move_base/status) actionlib_msgs/GoalStatusArray (10 Hz): the leg's goal
//           ACTIVE, then SUCCEEDED at the goal. With ~success_dwell and ~start_delay (s, default 0)
//           the robot stands still at a reached goal, then after a new goal became active, as a robot
//           that waits out a start warning would (demo.launch sets them for ProjectedPath's cues).
// tf:       map -> odom (fixed offset), odom -> base_link (robot pose) at ~tf_rate;
//           static base_link -> projector_link -> projector_optical_frame.

#include <actionlib_msgs/GoalStatusArray.h>
#include <geometry_msgs/Point32.h>
#include <geometry_msgs/PolygonStamped.h>
#include <geometry_msgs/PoseStamped.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/Marker.h>

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

constexpr double kPi = 3.14159265358979323846;

const char* const kMapFrame = "map";
const char* const kOdomFrame = "odom";
const char* const kBaseFrame = "base_link";
const char* const kProjectorFrame = "projector_link";
const char* const kProjectorOpticalFrame = "projector_optical_frame";

double wrapAngle(double angle)
{
  return std::atan2(std::sin(angle), std::cos(angle));
}

// ---------------------------------------------------------------------------------------------
// Small 2D geometry helpers
// ---------------------------------------------------------------------------------------------

struct Vec2
{
  double x{0.0};
  double y{0.0};
};

Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double norm(Vec2 a) { return std::hypot(a.x, a.y); }
double distance(Vec2 a, Vec2 b) { return norm(b - a); }

struct Pose2D
{
  double x{0.0};
  double y{0.0};
  double yaw{0.0};

  Vec2 position() const { return {x, y}; }
};

double distancePointToSegment(Vec2 p, Vec2 a, Vec2 b)
{
  const Vec2 ab = b - a;
  const double length_sq = dot(ab, ab);
  if (length_sq <= 0.0)
  {
    return distance(p, a);
  }
  const double t = std::clamp(dot(p - a, ab) / length_sq, 0.0, 1.0);
  return distance(p, a + ab * t);
}

double distancePointToPolyline(Vec2 p, const std::vector<Vec2>& polyline)
{
  if (polyline.size() == 1)
  {
    return distance(p, polyline.front());
  }
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i)
  {
    best = std::min(best, distancePointToSegment(p, polyline[i], polyline[i + 1]));
  }
  return best;
}

tf2::Transform toTransform(const Pose2D& pose)
{
  tf2::Quaternion q;
  q.setRPY(0.0, 0.0, pose.yaw);
  return tf2::Transform(q, tf2::Vector3(pose.x, pose.y, 0.0));
}

// ---------------------------------------------------------------------------------------------
// DetourPlanner: straight line if clear, otherwise one detour waypoint beside the obstacle,
// smoothed with Chaikin corner cutting so the path is a smooth curve.
// ---------------------------------------------------------------------------------------------

struct BoxObstacle
{
  Vec2 center;
  double size_x{0.3};
  double size_y{0.3};
  double height{0.6};

  double halfDiagonal() const { return 0.5 * std::hypot(size_x, size_y); }
};

class DetourPlanner
{
public:
  DetourPlanner(const BoxObstacle& obstacle, double robot_radius, double margin)
    : obstacle_(obstacle), clearance_(obstacle.halfDiagonal() + robot_radius + margin)
  {
  }

  // Required distance between the path and the obstacle centre.
  double clearance() const { return clearance_; }

  std::vector<Vec2> plan(Vec2 start, Vec2 goal) const
  {
    const Vec2 c = obstacle_.center;
    const double required = requiredClearance(start, goal);
    const std::vector<Vec2> straight{start, goal};
    const double length = distance(start, goal);
    if (length < 1e-6 || distancePointToPolyline(c, straight) >= required)
    {
      return straight;
    }

    // Detour waypoint: from the obstacle centre, perpendicular to the start-goal line, on the
    // side that gives the shorter path.
    const Vec2 dir = (goal - start) * (1.0 / length);
    const Vec2 normal{-dir.y, dir.x};
    const auto detourLength = [&](double side) {
      const Vec2 waypoint = c + normal * (side * clearance_);
      return distance(start, waypoint) + distance(waypoint, goal);
    };
    const double side = detourLength(+1.0) <= detourLength(-1.0) ? +1.0 : -1.0;

    // Corner cutting pulls the smoothed curve inwards, so push the waypoint out until the smoothed
    // path itself keeps the clearance.
    double offset = clearance_;
    std::vector<Vec2> path;
    for (int attempt = 0; attempt < kMaxInflations; ++attempt)
    {
      path = chaikin({start, c + normal * (side * offset), goal});
      const double closest = distancePointToPolyline(c, path);
      if (closest >= required)
      {
        break;
      }
      offset += (required - closest) + 0.01;
    }
    return path;
  }

private:
  static constexpr int kSmoothingIterations = 5;
  static constexpr int kMaxInflations = 40;

  // If the robot (or goal) is already closer than the clearance (e.g. it cut a corner), demanding
  // the full clearance is impossible; only demand that the path gets no closer than its ends.
  double requiredClearance(Vec2 start, Vec2 goal) const
  {
    const Vec2 c = obstacle_.center;
    return std::min({clearance_, distance(start, c) - 1e-3, distance(goal, c) - 1e-3});
  }

  // Chaikin corner cutting with fixed end points: every segment (a, b) is replaced by its 1/4 and
  // 3/4 points; converges to a quadratic B-spline that is tangent-continuous.
  static std::vector<Vec2> chaikin(std::vector<Vec2> points)
  {
    for (int iteration = 0; iteration < kSmoothingIterations && points.size() > 2; ++iteration)
    {
      std::vector<Vec2> refined;
      refined.reserve(2 * points.size());
      refined.push_back(points.front());
      for (std::size_t i = 0; i + 1 < points.size(); ++i)
      {
        const Vec2 a = points[i];
        const Vec2 b = points[i + 1];
        refined.push_back(a * 0.75 + b * 0.25);
        refined.push_back(a * 0.25 + b * 0.75);
      }
      refined.push_back(points.back());
      points = std::move(refined);
    }
    return points;
  }

  BoxObstacle obstacle_;
  double clearance_;
};

// ---------------------------------------------------------------------------------------------
// UnevenSampler: resamples a polyline the way a grid planner's output looks: random step lengths
// and, now and then, the same pose twice. Always starts at the first and ends at the last point.
// ---------------------------------------------------------------------------------------------

class UnevenSampler
{
public:
  UnevenSampler(double min_step, double max_step, double duplicate_probability, unsigned seed)
    : rng_(seed), step_(min_step, max_step), duplicate_(duplicate_probability)
  {
  }

  std::vector<Pose2D> sample(const std::vector<Vec2>& polyline)
  {
    std::vector<Pose2D> poses;
    if (polyline.empty())
    {
      return poses;
    }
    double yaw = initialYaw(polyline);
    poses.push_back({polyline.front().x, polyline.front().y, yaw});

    double to_next = step_(rng_);  // arc length still to travel before the next pose
    for (std::size_t i = 0; i + 1 < polyline.size(); ++i)
    {
      const Vec2 a = polyline[i];
      const Vec2 b = polyline[i + 1];
      const double length = distance(a, b);
      if (length < 1e-9)
      {
        continue;
      }
      yaw = std::atan2(b.y - a.y, b.x - a.x);
      double along = 0.0;
      while (along + to_next < length)
      {
        along += to_next;
        const Vec2 p = a + (b - a) * (along / length);
        poses.push_back({p.x, p.y, yaw});
        if (duplicate_(rng_))
        {
          poses.push_back(poses.back());
        }
        to_next = step_(rng_);
      }
      to_next -= length - along;
    }

    // End exactly on the goal (the last step is usually shorter than the others).
    const Vec2 goal = polyline.back();
    if (poses.size() > 1 && distance(poses.back().position(), goal) < 1e-3)
    {
      poses.pop_back();
    }
    poses.push_back({goal.x, goal.y, yaw});
    return poses;
  }

private:
  static double initialYaw(const std::vector<Vec2>& polyline)
  {
    for (std::size_t i = 0; i + 1 < polyline.size(); ++i)
    {
      const Vec2 d = polyline[i + 1] - polyline[i];
      if (norm(d) > 1e-9)
      {
        return std::atan2(d.y, d.x);
      }
    }
    return 0.0;
  }

  std::mt19937 rng_;
  std::uniform_real_distribution<double> step_;
  std::bernoulli_distribution duplicate_;
};

// ---------------------------------------------------------------------------------------------
// SimulatedRobot: unicycle kinematics in the map frame with a pure-pursuit path follower.
// ---------------------------------------------------------------------------------------------

struct RobotLimits
{
  double max_speed{0.4};         // m/s
  double max_turn_rate{1.2};     // rad/s
  double max_accel{0.6};         // m/s^2
  double max_turn_accel{4.0};    // rad/s^2
  double lookahead{0.4};         // m
  double min_approach_speed{0.08};  // m/s, so that the goal is actually reached
  double turn_in_place_gain{2.0};   // rad/s per rad of heading error when facing away from the path
};

class SimulatedRobot
{
public:
  SimulatedRobot(const Pose2D& start, const RobotLimits& limits) : pose_(start), limits_(limits) {}

  void setPlan(std::vector<Pose2D> plan) { plan_ = std::move(plan); }

  const Pose2D& pose() const { return pose_; }

  void step(double dt)
  {
    if (dt <= 0.0)
    {
      return;
    }
    double v_target = 0.0;
    double w_target = 0.0;
    computeCommand(v_target, w_target);

    // Acceleration limits keep the motion smooth when goals switch or the plan jumps.
    v_ += std::clamp(v_target - v_, -limits_.max_accel * dt, limits_.max_accel * dt);
    w_ += std::clamp(w_target - w_, -limits_.max_turn_accel * dt, limits_.max_turn_accel * dt);

    // Midpoint integration of the unicycle model.
    const double mid_yaw = pose_.yaw + 0.5 * w_ * dt;
    pose_.x += v_ * std::cos(mid_yaw) * dt;
    pose_.y += v_ * std::sin(mid_yaw) * dt;
    pose_.yaw = wrapAngle(pose_.yaw + w_ * dt);
  }

private:
  void computeCommand(double& v, double& w) const
  {
    if (plan_.empty())
    {
      return;
    }
    const Vec2 position = pose_.position();
    const Vec2 end = plan_.back().position();
    const Vec2 target = lookaheadPoint();
    const Vec2 to_target = target - position;
    const double target_distance = norm(to_target);
    if (target_distance < 1e-6)
    {
      return;
    }

    const double alpha = wrapAngle(std::atan2(to_target.y, to_target.x) - pose_.yaw);
    const double curvature = 2.0 * std::sin(alpha) / target_distance;  // pure pursuit arc
    const double heading_factor = std::max(0.0, std::cos(alpha));

    // Slow down when the target is off to the side (sharp turn), when the turn-rate limit could
    // not follow the arc at full speed, and when approaching the end of the plan.
    v = limits_.max_speed * heading_factor;
    if (std::abs(curvature) > 1e-9)
    {
      v = std::min(v, limits_.max_turn_rate / std::abs(curvature));
    }
    const double approach_speed = std::sqrt(2.0 * limits_.max_accel * distance(position, end));
    v = std::min(v, std::max(limits_.min_approach_speed, approach_speed));

    // Pure pursuit while roughly facing the path; blends into turning on the spot when facing away.
    w = v * curvature + limits_.turn_in_place_gain * alpha * (1.0 - heading_factor);
    w = std::clamp(w, -limits_.max_turn_rate, limits_.max_turn_rate);
  }

  // First plan pose at least `lookahead` away from the robot, searching forward from the pose
  // closest to the robot; the end of the plan if there is none.
  Vec2 lookaheadPoint() const
  {
    const Vec2 position = pose_.position();
    std::size_t closest = 0;
    double closest_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < plan_.size(); ++i)
    {
      const double d = distance(position, plan_[i].position());
      if (d < closest_distance)
      {
        closest_distance = d;
        closest = i;
      }
    }
    for (std::size_t i = closest; i < plan_.size(); ++i)
    {
      if (distance(position, plan_[i].position()) >= limits_.lookahead)
      {
        return plan_[i].position();
      }
    }
    return plan_.back().position();
  }

  Pose2D pose_;
  RobotLimits limits_;
  std::vector<Pose2D> plan_;  // latest plan, in the map frame
  double v_{0.0};
  double w_{0.0};
};

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

    const ros::Time now = ros::Time::now();
    publishObstacle(now);
    broadcastRobotTf(now);
    last_step_ = ros::SteadyTime::now();
    startLeg(1, now);

    control_timer_ = nh_.createTimer(ros::Duration(1.0 / tf_rate), &DemoNavigation::onControl, this);
    replan_timer_ = nh_.createTimer(ros::Duration(1.0 / replan_rate), &DemoNavigation::onReplan, this);
    footprint_timer_ = nh_.createTimer(ros::Duration(0.1), &DemoNavigation::onFootprint, this);
    obstacle_timer_ = nh_.createTimer(ros::Duration(1.0), &DemoNavigation::onObstacle, this);
  }

private:
  static constexpr double kRobotRadius = 0.3;
  static constexpr double kClearanceMargin = 0.1;
  static constexpr double kGoalTolerance = 0.05;
  static constexpr double kMaxStep = 0.1;  // s; larger wall-clock gaps (e.g. suspended) are clipped
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

  void onControl(const ros::TimerEvent&)
  {
    // Simulate with the real elapsed (monotonic wall-clock) time, so timer jitter doesn't change
    // the robot's speed.
    const ros::SteadyTime steady_now = ros::SteadyTime::now();
    const double dt = std::clamp((steady_now - last_step_).toSec(), 0.0, kMaxStep);
    last_step_ = steady_now;
    const ros::Time now = ros::Time::now();
    if (now >= hold_until_)
    {
      robot_.step(dt);  // otherwise: standing still (start delay, or dwelling at a reached goal)
    }
    broadcastRobotTf(now);

    if (dwelling_)
    {
      if (now >= hold_until_)
      {
        dwelling_ = false;
        startLeg((goal_index_ + 1) % goals_.size(), now);
      }
      return;
    }
    const Vec2 goal = goals_[goal_index_];
    if (distance(robot_.pose().position(), goal) < kGoalTolerance)
    {
      ROS_INFO("demo_navigation: reached goal %zu (%.2f, %.2f) after %.1f s", goal_index_, goal.x,
               goal.y, (now - leg_start_).toSec());
      goal_status_ = actionlib_msgs::GoalStatus::SUCCEEDED;
      publishStatus(now);
      if (success_dwell_ > 0.0)
      {
        dwelling_ = true;
        hold_until_ = now + ros::Duration(success_dwell_);
        return;
      }
      startLeg((goal_index_ + 1) % goals_.size(), now);
    }
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

  void onReplan(const ros::TimerEvent&)
  {
    // Re-broadcast the (unchanged) robot pose with the plan's stamp first, so consumers can
    // transform the plan at its own stamp right away instead of waiting for the next tf tick.
    const ros::Time now = ros::Time::now();
    broadcastRobotTf(now);
    replan(now);
  }

  void onFootprint(const ros::TimerEvent&)
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
    publishStatus(footprint.header.stamp);
  }

  void onObstacle(const ros::TimerEvent&) { publishObstacle(ros::Time::now()); }

  // --- navigation ----------------------------------------------------------------------------

  void startLeg(std::size_t goal_index, const ros::Time& stamp)
  {
    const Vec2 from = robot_.pose().position();
    goal_index_ = goal_index;
    leg_start_ = stamp;
    ++goal_count_;
    goal_status_ = actionlib_msgs::GoalStatus::ACTIVE;
    hold_until_ = stamp + ros::Duration(start_delay_);
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
  ros::Time leg_start_;
  ros::SteadyTime last_step_;

  ros::Publisher path_pub_;
  ros::Publisher goal_pub_;
  ros::Publisher status_pub_;
  double start_delay_{0.0};
  double success_dwell_{0.0};
  ros::Time hold_until_;
  bool dwelling_{false};
  unsigned goal_count_{0};
  std::uint8_t goal_status_{actionlib_msgs::GoalStatus::ACTIVE};
  ros::Publisher obstacle_pub_;
  ros::Publisher footprint_pub_;
  ros::Publisher camera_info_pub_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;

  ros::Timer control_timer_;
  ros::Timer replan_timer_;
  ros::Timer footprint_timer_;
  ros::Timer obstacle_timer_;
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
