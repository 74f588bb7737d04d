#include "rviz_projector/ros/ros_conversions.h"

#include "rviz_projector/core/path_style_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace rviz_projector
{
bool isFinitePose(const geometry_msgs::Pose& pose)
{
  const double values[] = {pose.position.x,    pose.position.y,    pose.position.z,   pose.orientation.x,
                           pose.orientation.y, pose.orientation.z, pose.orientation.w};
  return std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); });
}

std::size_t pathToFloorPoints(const nav_msgs::Path& path, const RigidTransform& path_to_target,
                              std::vector<Vec2>& out)
{
  out.clear();
  out.reserve(path.poses.size());
  std::size_t dropped = 0;
  for (const auto& stamped : path.poses)
  {
    if (!isFinitePose(stamped.pose))
    {
      ++dropped;
      continue;
    }
    const geometry_msgs::Point& p = stamped.pose.position;
    const Vec3 q = path_to_target.apply(Vec3{p.x, p.y, p.z});
    if (!(std::abs(q.x) <= path_style::kMaxFloorCoordinate && std::abs(q.y) <= path_style::kMaxFloorCoordinate))
    {
      ++dropped;  // out of range: cannot be drawn (and overflows transforms of 1e308)
      continue;
    }
    out.push_back(Vec2{q.x, q.y});
  }
  return dropped;
}

RigidTransform toRigidTransform(const geometry_msgs::Transform& transform)
{
  const geometry_msgs::Quaternion& q = transform.rotation;
  const geometry_msgs::Vector3& v = transform.translation;
  return RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, Vec3{v.x, v.y, v.z});
}

LensCalibration toLensCalibration(const sensor_msgs::CameraInfo& info)
{
  LensCalibration c;
  c.width = info.width;
  c.height = info.height;
  c.distortion_model = info.distortion_model;
  c.D = info.D;
  std::copy(info.K.begin(), info.K.end(), c.K.begin());
  std::copy(info.P.begin(), info.P.end(), c.P.begin());
  c.binning_x = info.binning_x;
  c.binning_y = info.binning_y;
  c.roi_x_offset = info.roi.x_offset;
  c.roi_y_offset = info.roi.y_offset;
  c.roi_width = info.roi.width;
  c.roi_height = info.roi.height;
  return c;
}

std::string readCloudXyz(const sensor_msgs::PointCloud2& cloud, std::vector<Vec3>& out)
{
  out.clear();
  if (cloud.is_bigendian)
  {
    return "big-endian data is not supported";
  }
  std::uint64_t offsets[3] = {0, 0, 0};
  const char* names[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis)
  {
    bool found = false;
    for (const sensor_msgs::PointField& field : cloud.fields)
    {
      if (field.name == names[axis])
      {
        if (field.datatype != sensor_msgs::PointField::FLOAT32 || field.count != 1)
        {
          return std::string("field '") + names[axis] + "' is not a single FLOAT32";
        }
        if (std::uint64_t(field.offset) + sizeof(float) > cloud.point_step)
        {
          return std::string("field '") + names[axis] + "' does not fit in point_step";
        }
        offsets[axis] = field.offset;
        found = true;
        break;
      }
    }
    if (!found)
    {
      return std::string("no field '") + names[axis] + "'";
    }
  }
  // 32-bit sizes: their products fit in 64 bits.
  const std::uint64_t row_bytes = std::uint64_t(cloud.width) * cloud.point_step;
  if (row_bytes > cloud.row_step)
  {
    return "width x point_step is larger than row_step";
  }
  if (std::uint64_t(cloud.height) * cloud.row_step > cloud.data.size())
  {
    return "data shorter than height x row_step";
  }
  out.reserve(std::size_t(cloud.width) * cloud.height);
  for (std::uint64_t row = 0; row < cloud.height; ++row)
  {
    const std::uint8_t* point = cloud.data.data() + row * cloud.row_step;
    for (std::uint64_t column = 0; column < cloud.width; ++column, point += cloud.point_step)
    {
      float xyz[3];
      for (int axis = 0; axis < 3; ++axis)
      {
        std::memcpy(&xyz[axis], point + offsets[axis], sizeof(float));  // no alignment assumed
      }
      out.push_back(Vec3{xyz[0], xyz[1], xyz[2]});
    }
  }
  return std::string();
}
}  // namespace rviz_projector
