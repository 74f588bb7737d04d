// The reference system's path -> markers step (HRI 2022 "Projecting Robot Navigation Paths"),
// re-implemented from its description (../shared/README.md, the paper's Algorithm 1) as the
// baseline the microbenchmarks compare against. Deliberately straightforward, like the original:
//  - every pose is transformed odom -> map on its own (a tf lookup per pose),
//  - the walk back from the destination uses std::vector::at and ends by catching
//    std::out_of_range (an empty path is not checked: callers must not pass one),
//  - kept points are geometry_msgs::Point, and every arrow is its own visualization_msgs::Marker
//    in a MarkerArray (plus a sphere for the destination).
// Not used by the package; benchmark code only.
#pragma once

#include <string>
#include <vector>

#include <geometry_msgs/Point.h>
#include <geometry_msgs/PoseStamped.h>
#include <nav_msgs/Path.h>
#include <visualization_msgs/MarkerArray.h>

namespace tf2
{
class BufferCore;
}

namespace reference_baseline
{
/// The reference robot's numbers (../shared/README.md).
struct Parameters
{
  double min_distance = 0.10;     // D: kept points at least this far apart
  double circle_diameter = 0.12;  // the first gap is D + this (room for the goal circle)
  double shaft_diameter = 0.06;
  double head_diameter = 0.08;
  double head_length = 0.08;
  double sphere_diameter = 0.12;
  double lifetime = 10.0;  // seconds
  std::string frame = "map";
};

/// Each pose transformed into `target_frame` with its own lookup (what the reference node does).
std::vector<geometry_msgs::PoseStamped> transformPoses(const nav_msgs::Path& path, const tf2::BufferCore& tf,
                                                       const std::string& target_frame);

/// Algorithm 1: kept points, destination first. Precondition: `poses` is not empty.
std::vector<geometry_msgs::Point> sparsePoints(const std::vector<geometry_msgs::PoseStamped>& poses,
                                               const Parameters& parameters);

/// One ARROW marker per consecutive pair of kept points (tail = odd, tip = even) and a SPHERE at
/// the destination.
visualization_msgs::MarkerArray toMarkers(const std::vector<geometry_msgs::Point>& kept, const Parameters& parameters);
}  // namespace reference_baseline
