#include "mount_oracle.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include <camera_calibration_parsers/parse.h>

#include "../core/mount_test_oracle.h"

namespace rviz_projector_test
{
TestPose opticalPoseByHand(const TestMount& m)
{
  // The rotation built by hand in the core tests' oracle (elementary rotations multiplied out).
  const mount_oracle::Mat r = mount_oracle::parentROptical({m.x, m.y, m.z, m.roll, m.pitch, m.yaw});
  TestPose pose;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      pose.rotation(i, j) = r[i][j];
    }
  }
  pose.translation = cv::Vec3d(m.x, m.y, m.z);
  return pose;
}

bool lensFromFile(const std::string& path, image_geometry::PinholeCameraModel& lens)
{
  std::string name;
  sensor_msgs::CameraInfo info;
  return camera_calibration_parsers::readCalibration(path, name, info) && lens.fromCameraInfo(info);
}

bool pixelOnPlane(const image_geometry::PinholeCameraModel& lens, const TestPose& pose, double u, double v,
                  double plane_z, cv::Vec3d& out)
{
  const cv::Point3d ray = lens.projectPixelTo3dRay(cv::Point2d(u, v));
  const cv::Vec3d direction = pose.rotation * cv::Vec3d(ray.x, ray.y, ray.z);
  if (std::abs(direction[2]) < 1e-12)
  {
    return false;
  }
  const double s = (plane_z - pose.translation[2]) / direction[2];
  if (s <= 0.0)
  {
    return false;
  }
  out = pose.translation + s * direction;
  return true;
}

std::string pointsYaml(const std::string& frame, const std::vector<TestPoint>& points, bool with_pixels)
{
  std::ostringstream text;
  text << std::setprecision(12) << "frame: " << frame << "\npoints:\n";
  for (const TestPoint& p : points)
  {
    text << "  - {id: " << p.id;
    if (with_pixels)
    {
      text << ", u: " << p.u << ", v: " << p.v;
    }
    text << ", x: " << p.world[0] << ", y: " << p.world[1];
    if (p.world[2] != 0.0)
    {
      text << ", z: " << p.world[2];
    }
    text << "}\n";
  }
  return text.str();
}
}  // namespace rviz_projector_test
