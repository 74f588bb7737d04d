// ROS message -> core type conversions shared by the displays and nodes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <nav_msgs/Path.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/PointCloud2.h>

#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/core/vec2.h"
#include "rviz_projector/core/vec3.h"

namespace rviz_projector
{
/// True when every number of the pose (position and orientation) is finite.
bool isFinitePose(const geometry_msgs::Pose& pose);

/**
 * Floor positions (x, y in the target frame) of a path's poses, transformed by `path_to_target`.
 * Poses with a NaN/Inf anywhere, or beyond path_style::kMaxFloorCoordinate on the floor, are
 * skipped; returns how many. `out` is cleared first and keeps
 * its capacity between calls.
 */
std::size_t pathToFloorPoints(const nav_msgs::Path& path, const RigidTransform& path_to_target,
                              std::vector<Vec2>& out);

/// A tf transform (e.g. from tf2's lookupTransform) as a core transform.
RigidTransform toRigidTransform(const geometry_msgs::Transform& transform);

LensCalibration toLensCalibration(const sensor_msgs::CameraInfo& info);

/**
 * The x, y, z of every point of a PointCloud2 (FLOAT32 fields "x", "y", "z", count 1), in the
 * cloud's own frame, row by row honouring row_step (rows may be padded). Checked before anything is
 * read, without integer overflow: the fields exist and fit in point_step, width * point_step fits
 * in row_step, height * row_step fits in data; a big-endian cloud is refused (not converted).
 * `out` is cleared first; returns an empty string on success, else what is wrong (and `out` is empty).
 */
std::string readCloudXyz(const sensor_msgs::PointCloud2& cloud, std::vector<Vec3>& out);
}  // namespace rviz_projector
