// A simulated planar laser scanner seeing circles (a pedestrian's body, legs): what the demo's
// pedestrian node publishes as a sensor_msgs/LaserScan. Plain geometry (no ROS).
#pragma once

#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// The beams of a scan: as sensor_msgs/LaserScan describes them.
struct ScanGeometry
{
  double angle_min = -2.35619449;   ///< radians, counter-clockwise from the scanner's x axis
  double angle_increment = 0.00436332313;  ///< radians between beams (> 0)
  int beams = 1081;
  double range_min = 0.05;
  double range_max = 10.0;
};

/// A vertical cylinder seen by the scanner: centre on the floor plane and radius, metres.
struct Circle
{
  Vec2 centre;
  double radius = 0.0;
};

/**
 * The ranges of one scan from a scanner at `origin` heading `yaw` (radians, in the circles' frame):
 * beam i points at yaw + angle_min + i * angle_increment; its range is the distance to the nearest
 * circle it hits from outside, or +infinity (no return, as LaserScan encodes "nothing within
 * range_max") when it hits none within range_max. A scanner inside a circle sees that circle at
 * range_min. `ranges` is resized to `beams` (kept capacity). Non-finite inputs: all +infinity.
 */
void simulateScan(const ScanGeometry& geometry, const Vec2& origin, double yaw, const std::vector<Circle>& circles,
                  std::vector<float>& ranges);
}  // namespace rviz_projector
