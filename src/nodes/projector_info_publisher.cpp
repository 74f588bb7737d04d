// projector_info_publisher: publishes a projector's calibration as a latched sensor_msgs/CameraInfo.
//
// Loads a calibration file in the standard ROS format (the YAML that camera_calibration_parsers
// reads and ROS camera calibration tools write), checks it, stamps it with the projector's optical
// frame and publishes it once, latched. A missing, malformed or unusable file is a ROS_FATAL that
// names the file and the field, and the node exits with status 1.
//
// Parameters: ~calibration_file  path, package://<pkg>/<path> or file:///<path> (required); a
//                                relative path is taken from ~base_directory
//             ~base_directory    directory of a relative calibration_file (projector.launch: $PWD)
//             ~frame_id          optical frame of the projector (projector_optical_frame)
//             ~topic             topic to publish on (camera_info; remapping camera_info works too)
// Publishes:  camera_info (or ~topic)  sensor_msgs/CameraInfo, latched

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>

#include <string>

#include "rviz_projector/calibration/calibration_file.h"

namespace
{
const char* const kName = "projector_info_publisher";
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, kName);
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");

  std::string url;
  if (!pnh.getParam("calibration_file", url) || url.empty())
  {
    ROS_FATAL("%s: parameter %s is not set: give it the calibration YAML of the projector, e.g. "
              "$(find rviz_projector)/config/pa503w.yaml or package://rviz_projector/config/pa503w.yaml",
              kName, pnh.resolveName("calibration_file").c_str());
    return 1;
  }
  const std::string frame_id = pnh.param<std::string>("frame_id", "projector_optical_frame");
  const std::string topic = pnh.param<std::string>("topic", "camera_info");
  if (frame_id.empty())
  {
    ROS_FATAL("%s: parameter %s is empty: give the projector's optical frame", kName,
              pnh.resolveName("frame_id").c_str());
    return 1;
  }

  // A relative path is taken from ~base_directory (projector.launch: roslaunch's working directory,
  // since roslaunch runs its nodes in ~/.ros), as mount_tf_publisher does for mount_file.
  std::string path;
  if (rviz_projector::resolveCalibrationUrl(url, path).empty())
  {
    url = rviz_projector::inDirectory(path, pnh.param<std::string>("base_directory", ""));
  }
  rviz_projector::CalibrationFile calibration;
  const std::string error = rviz_projector::loadCalibrationFile(url, calibration);
  if (!error.empty())
  {
    ROS_FATAL("%s: %s", kName, error.c_str());
    return 1;
  }
  for (const std::string& warning : calibration.warnings)
  {
    ROS_WARN("%s: %s: %s", kName, calibration.path.c_str(), warning.c_str());
  }

  sensor_msgs::CameraInfo info = calibration.info;
  info.header.frame_id = frame_id;
  info.header.stamp = ros::Time::now();
  ros::Publisher publisher = nh.advertise<sensor_msgs::CameraInfo>(topic, 1, true);
  publisher.publish(info);
  ROS_INFO("%s: '%s' from %s: %ux%u, fx %g fy %g cx %g cy %g (P), frame %s, latched on %s", kName,
           calibration.camera_name.c_str(), calibration.path.c_str(), info.width, info.height, info.P[0], info.P[5],
           info.P[2], info.P[6], frame_id.c_str(), publisher.getTopic().c_str());
  ros::spin();
  return 0;
}
