// The demo robot's world, for demo_navigation: planar geometry, a planner that detours around one
// box obstacle, a sampler that makes its path look like a grid planner's, and a unicycle robot with a
// pure-pursuit follower. Plain C++ and tf2's LinearMath (no ROS node): the node glues them together.
#pragma once

#include <tf2/LinearMath/Quaternion.h>
#include <tf2/LinearMath/Transform.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "rviz_projector/core/angle.h"

namespace rviz_projector_demo
{
constexpr double kPi = 3.14159265358979323846;

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
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double norm(Vec2 a) { return std::hypot(a.x, a.y); }
inline double distance(Vec2 a, Vec2 b) { return norm(b - a); }

struct Pose2D
{
  double x{0.0};
  double y{0.0};
  double yaw{0.0};

  Vec2 position() const { return {x, y}; }
};

inline double distancePointToSegment(Vec2 p, Vec2 a, Vec2 b)
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

inline double distancePointToPolyline(Vec2 p, const std::vector<Vec2>& polyline)
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

inline tf2::Transform toTransform(const Pose2D& pose)
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
  /// Forward speed (m/s) and turn rate (rad/s) of the last step: the odometry's twist.
  double speed() const { return v_; }
  double turnRate() const { return w_; }

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
    pose_.yaw = rviz_projector::wrapToPi(pose_.yaw + w_ * dt);
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

    const double alpha = rviz_projector::wrapToPi(std::atan2(to_target.y, to_target.x) - pose_.yaw);
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
}  // namespace rviz_projector_demo
