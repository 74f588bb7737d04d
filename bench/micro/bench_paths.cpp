#include "bench_paths.h"

#include <cmath>
#include <map>
#include <random>

#include "rviz_projector/core/path_spacer.h"

namespace rviz_projector_bench
{
namespace
{
struct PlannerPose
{
  double x, y, yaw;
};

std::vector<PlannerPose> generate(std::size_t poses)
{
  std::vector<PlannerPose> out;
  out.reserve(poses);
  std::mt19937 rng(20220307u);
  std::uniform_real_distribution<double> step(0.01, 0.04);
  std::bernoulli_distribution duplicate(0.02);
  double x = 0.0, y = 0.0, s = 0.0;
  while (out.size() < poses)
  {
    // Heading wanders slowly (curvature at most ~0.7 /m): a meandering corridor-like path.
    const double yaw = 0.8 * std::sin(0.35 * s) + 0.3 * std::sin(1.3 * s);
    out.push_back({x, y, yaw});
    if (out.size() < poses && duplicate(rng))
    {
      out.push_back(out.back());
    }
    const double ds = step(rng);
    x += ds * std::cos(yaw);
    y += ds * std::sin(yaw);
    s += ds;
  }
  return out;
}

const std::vector<PlannerPose>& plannerPath(std::size_t poses)
{
  static std::map<std::size_t, std::vector<PlannerPose>> cache;
  auto it = cache.find(poses);
  if (it == cache.end())
  {
    it = cache.emplace(poses, generate(poses)).first;
  }
  return it->second;
}
}  // namespace

const std::vector<rviz_projector::Vec2>& planarPath(std::size_t poses)
{
  static std::map<std::size_t, std::vector<rviz_projector::Vec2>> cache;
  auto it = cache.find(poses);
  if (it == cache.end())
  {
    std::vector<rviz_projector::Vec2> points;
    points.reserve(poses);
    for (const PlannerPose& p : plannerPath(poses))
    {
      points.push_back({p.x, p.y});
    }
    it = cache.emplace(poses, std::move(points)).first;
  }
  return it->second;
}

const nav_msgs::Path& pathMessage(std::size_t poses)
{
  static std::map<std::size_t, nav_msgs::Path> cache;
  auto it = cache.find(poses);
  if (it == cache.end())
  {
    nav_msgs::Path path;
    path.header.frame_id = "odom";
    path.header.stamp = ros::Time(1000, 0);
    path.poses.resize(poses);
    const std::vector<PlannerPose>& planner = plannerPath(poses);
    for (std::size_t i = 0; i < poses; ++i)
    {
      geometry_msgs::PoseStamped& ps = path.poses[i];
      ps.header = path.header;
      ps.pose.position.x = planner[i].x;
      ps.pose.position.y = planner[i].y;
      ps.pose.orientation.z = std::sin(0.5 * planner[i].yaw);
      ps.pose.orientation.w = std::cos(0.5 * planner[i].yaw);
    }
    it = cache.emplace(poses, std::move(path)).first;
  }
  return it->second;
}

const std::vector<rviz_projector::Arrow>& arrows(std::size_t count)
{
  static std::map<std::size_t, std::vector<rviz_projector::Arrow>> cache;
  auto it = cache.find(count);
  if (it == cache.end())
  {
    rviz_projector::SpacingParameters parameters;
    parameters.max_arrows = count;
    rviz_projector::PathSpacer spacer(parameters);
    // Default spacing 0.25 m; poses every 0.025 m on average: 12 poses per arrow, plus margin.
    const std::size_t poses = count * 12 + 1000;
    it = cache.emplace(count, spacer.space(planarPath(poses)).arrows).first;
  }
  return it->second;
}

std::vector<rviz_projector::Vec2> litRectangle(const rviz_projector::Vec2& robot, double heading, double near,
                                               double far, double half)
{
  using rviz_projector::Vec2;
  const Vec2 forward{std::cos(heading), std::sin(heading)};
  const Vec2 left = rviz_projector::perpendicular(forward);
  const Vec2 corners[4] = {{near, half}, {far, half}, {far, -half}, {near, -half}};
  std::vector<Vec2> outline;
  for (int c = 0; c < 4; ++c)
  {
    for (int k = 0; k < 8; ++k)
    {
      const Vec2 local = corners[c] + (corners[(c + 1) % 4] - corners[c]) * (k / 8.0);
      outline.push_back(robot + forward * local.x + left * local.y);
    }
  }
  return outline;
}
}  // namespace rviz_projector_bench
