#include "mount_oracle.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include <camera_calibration_parsers/parse.h>

namespace rviz_projector_test
{
TestPose opticalPoseByHand(const TestMount& m)
{
  const double cr = std::cos(m.roll), sr = std::sin(m.roll);
  const double cp = std::cos(m.pitch), sp = std::sin(m.pitch);
  const double cy = std::cos(m.yaw), sy = std::sin(m.yaw);
  const cv::Matx33d rx(1, 0, 0, 0, cr, -sr, 0, sr, cr);
  const cv::Matx33d ry(cp, 0, sp, 0, 1, 0, -sp, 0, cp);
  const cv::Matx33d rz(cy, -sy, 0, sy, cy, 0, 0, 0, 1);
  // Columns: the optical axes in the body frame (x right = -y body, y down = -z body, z = x body).
  const cv::Matx33d body_optical(0, 0, 1, -1, 0, 0, 0, -1, 0);
  TestPose pose;
  pose.rotation = rz * ry * rx * body_optical;
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
