// Test oracle for the calibration tests: where a projector pixel lands on the floor, computed
// independently of the code under test: the mount's rotation built by hand from its roll, pitch,
// yaw (projector.launch's convention as documented: R = Rz(yaw) Ry(pitch) Rx(roll), then the
// standard body -> optical axes), rays by image_geometry::PinholeCameraModel on the raw CameraInfo.
#pragma once

#include <string>
#include <vector>

#include <image_geometry/pinhole_camera_model.h>
#include <opencv2/core.hpp>

namespace rviz_projector_test
{
struct TestMount
{
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double roll = 0.0;
  double pitch = 0.0;
  double yaw = 0.0;
};

/// Optical frame pose in the parent frame: p_parent = rotation * p_optical + translation.
struct TestPose
{
  cv::Matx33d rotation = cv::Matx33d::eye();
  cv::Vec3d translation;
};

TestPose opticalPoseByHand(const TestMount& mount);

/// The lens of a calibration file, read with camera_calibration_parsers; false when unreadable.
bool lensFromFile(const std::string& path, image_geometry::PinholeCameraModel& lens);

/// Where the ray through pixel (u, v) meets the plane z = plane_z; false when it does not.
bool pixelOnPlane(const image_geometry::PinholeCameraModel& lens, const TestPose& pose, double u, double v,
                  double plane_z, cv::Vec3d& out);

struct TestPoint
{
  int id = 0;
  double u = 0.0;
  double v = 0.0;
  cv::Vec3d world;
};

/// A points.yaml (the format); `with_pixels` false leaves u, v out.
std::string pointsYaml(const std::string& frame, const std::vector<TestPoint>& points, bool with_pixels = true);
}  // namespace rviz_projector_test
