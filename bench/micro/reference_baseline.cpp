#include "reference_baseline.h"

#include <cmath>
#include <stdexcept>

#include <tf2/buffer_core.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>

namespace reference_baseline
{
std::vector<geometry_msgs::PoseStamped> transformPoses(const nav_msgs::Path& path, const tf2::BufferCore& tf,
                                                       const std::string& target_frame)
{
  std::vector<geometry_msgs::PoseStamped> out;
  for (const geometry_msgs::PoseStamped& pose : path.poses)
  {
    const geometry_msgs::TransformStamped t =
        tf.lookupTransform(target_frame, pose.header.frame_id, ros::Time(0));
    geometry_msgs::PoseStamped transformed;
    tf2::doTransform(pose, transformed, t);
    out.push_back(transformed);
  }
  return out;
}

std::vector<geometry_msgs::Point> sparsePoints(const std::vector<geometry_msgs::PoseStamped>& poses,
                                               const Parameters& parameters)
{
  std::vector<geometry_msgs::Point> kept;
  const int last = static_cast<int>(poses.size()) - 1;
  int i = last;
  do
  {
    const geometry_msgs::Point p = poses.at(i).pose.position;
    kept.push_back(p);
    int j = i;
    try
    {
      double d = 0.0;
      do
      {
        --j;
        // A negative index becomes a huge size_t: at() throws, which ends the walk.
        const geometry_msgs::Point q = poses.at(static_cast<std::size_t>(j)).pose.position;
        d = std::sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y));
      } while (d < parameters.min_distance ||
               (i == last && d < parameters.min_distance + parameters.circle_diameter));
    }
    catch (const std::out_of_range&)
    {
      // Walked off the start of the path: done.
    }
    i = j;
  } while (i > 0);
  return kept;
}

visualization_msgs::MarkerArray toMarkers(const std::vector<geometry_msgs::Point>& kept, const Parameters& parameters)
{
  visualization_msgs::MarkerArray array;
  const ros::Time stamp(1000, 0);
  int id = 0;
  for (std::size_t k = 0; k + 1 < kept.size(); k += 2)
  {
    visualization_msgs::Marker arrow;
    arrow.header.frame_id = parameters.frame;
    arrow.header.stamp = stamp;
    arrow.ns = "path_arrows";
    arrow.id = id++;
    arrow.type = visualization_msgs::Marker::ARROW;
    arrow.action = visualization_msgs::Marker::ADD;
    arrow.pose.orientation.w = 1.0;
    arrow.points.push_back(kept[k + 1]);  // tail
    arrow.points.push_back(kept[k]);      // tip
    arrow.scale.x = parameters.shaft_diameter;
    arrow.scale.y = parameters.head_diameter;
    arrow.scale.z = parameters.head_length;
    arrow.color.r = 1.0f;
    arrow.color.g = 0.0f;
    arrow.color.b = 1.0f;
    arrow.color.a = 1.0f;
    arrow.lifetime = ros::Duration(parameters.lifetime);
    array.markers.push_back(arrow);
  }
  if (!kept.empty())
  {
    visualization_msgs::Marker sphere;
    sphere.header.frame_id = parameters.frame;
    sphere.header.stamp = stamp;
    sphere.ns = "path_goal";
    sphere.id = 0;
    sphere.type = visualization_msgs::Marker::SPHERE;
    sphere.action = visualization_msgs::Marker::ADD;
    sphere.pose.position = kept.front();
    sphere.pose.orientation.w = 1.0;
    sphere.scale.x = sphere.scale.y = sphere.scale.z = parameters.sphere_diameter;
    sphere.color.g = 1.0f;
    sphere.color.a = 1.0f;
    sphere.lifetime = ros::Duration(parameters.lifetime);
    array.markers.push_back(sphere);
  }
  return array;
}
}  // namespace reference_baseline
