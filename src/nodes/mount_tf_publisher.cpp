// mount_tf_publisher: the projector's mount from a mount file (calibrate_projector --output) as a
// static tf, for projector.launch mount_file:= (issue 12).
//
// Publishes parent_frame (from the file) -> ~frame with the file's x y z roll pitch yaw exactly as
// tf2_ros static_transform_publisher does for "x y z yaw pitch roll parent frame": translation
// x y z, rotation tf2::Quaternion::setRPY(roll, pitch, yaw). A missing or broken file is a
// ROS_FATAL naming the file and the field, and the node exits with status 1.
//
// Parameters: ~mount_file      the mount YAML (a path, package://<pkg>/<path> or file:///<path>);
//                              a relative path is taken from ~base_directory
//             ~base_directory  directory of relative paths (projector.launch: roslaunch's $PWD)
//             ~frame           the projector's body frame (projector_link)

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <string>

#include "rviz_projector/calibration/calibration_file.h"
#include "rviz_projector/calibration/mount_file.h"

namespace
{
const char* const kName = "mount_tf_publisher";
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, kName);
  ros::NodeHandle pnh("~");

  std::string url;
  if (!pnh.getParam("mount_file", url) || url.empty())
  {
    ROS_FATAL("%s: parameter %s is not set: give it the mount YAML written by calibrate_projector --output",
              kName, pnh.resolveName("mount_file").c_str());
    return 1;
  }
  const std::string frame = pnh.param<std::string>("frame", "projector_link");
  if (frame.empty())
  {
    ROS_FATAL("%s: parameter %s is empty: give the projector's body frame", kName, pnh.resolveName("frame").c_str());
    return 1;
  }
  std::string path;
  const std::string url_error = rviz_projector::resolveCalibrationUrl(url, path);
  if (!url_error.empty())
  {
    ROS_FATAL("%s: mount_file %s: %s", kName, url.c_str(), url_error.c_str());
    return 1;
  }
  path = rviz_projector::inDirectory(path, pnh.param<std::string>("base_directory", ""));

  rviz_projector::MountFile mount_file;
  const std::string error = rviz_projector::readMountFile(path, mount_file);
  if (!error.empty())
  {
    ROS_FATAL("%s: mount_file %s", kName, error.c_str());
    return 1;
  }
  if (mount_file.parent_frame == frame)
  {
    ROS_FATAL("%s: mount_file %s: parent_frame '%s' is the projector's own frame", kName, path.c_str(),
              frame.c_str());
    return 1;
  }

  const rviz_projector::ProjectorMount& m = mount_file.mount;
  geometry_msgs::TransformStamped transform;
  transform.header.stamp = ros::Time::now();
  transform.header.frame_id = mount_file.parent_frame;
  transform.child_frame_id = frame;
  transform.transform.translation.x = m.x;
  transform.transform.translation.y = m.y;
  transform.transform.translation.z = m.z;
  tf2::Quaternion rotation;
  rotation.setRPY(m.roll, m.pitch, m.yaw);
  transform.transform.rotation.x = rotation.x();
  transform.transform.rotation.y = rotation.y();
  transform.transform.rotation.z = rotation.z();
  transform.transform.rotation.w = rotation.w();

  tf2_ros::StaticTransformBroadcaster broadcaster;
  broadcaster.sendTransform(transform);
  ROS_INFO("%s: mount from %s: %s -> %s, x %g y %g z %g m, roll %g pitch %g yaw %g rad", kName, path.c_str(),
           mount_file.parent_frame.c_str(), frame.c_str(), m.x, m.y, m.z, m.roll, m.pitch, m.yaw);
  ros::spin();
  return 0;
}
