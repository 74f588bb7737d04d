// Paths for the microbenchmarks: what a grid planner publishes (unevenly spaced poses along a
// smooth curve, now and then the same pose twice), deterministic and cached per size.
#pragma once

#include <cstddef>
#include <vector>

#include <nav_msgs/Path.h>

#include "rviz_projector/core/arrow.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector_bench
{
/// Mean distance between consecutive poses, metres (steps are uniform in [0.01, 0.04]).
constexpr double kMeanPoseStep = 0.025;

/// Planar positions of an n-pose path (start -> destination), cached.
const std::vector<rviz_projector::Vec2>& planarPath(std::size_t poses);

/// The same path as a nav_msgs/Path in frame "odom" (orientation along the path), cached.
const nav_msgs::Path& pathMessage(std::size_t poses);

/// Exactly `count` arrows, as the spacer places them (Exact mode, default spacing) along a path
/// long enough; cached.
const std::vector<rviz_projector::Arrow>& arrows(std::size_t count);

/// A lit area as FloorFootprint's outline gives it: the rectangle [near, far] x [-half, half] in
/// the frame of a robot at `robot` heading `heading`, 8 points per side, clockwise.
std::vector<rviz_projector::Vec2> litRectangle(const rviz_projector::Vec2& robot, double heading, double near,
                                               double far, double half);
}  // namespace rviz_projector_bench
