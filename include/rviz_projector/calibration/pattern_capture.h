// calibrate_projector --camera (issue 24): showing patterns through the running projector and
// capturing what the robot's camera sees of each. The ROS half of the camera calibration.
//
// Protocol (the ProjectorCamera's Pattern topic, doc/reference/displays.md):
//  1. publish the pattern (sensor_msgs/Image, mono8) stamped with a fresh, unique stamp;
//  2. wait for its header on <pattern topic>/shown: it is on the screen now (timeout: an error that
//     names the topic);
//  3. wait `settle` seconds of ROS time (the projector's own lag and the camera's exposure);
//  4. take the first camera frame stamped at or after (acknowledgement + settle): a frame exposed
//     before the pattern was surely on the floor is never used.
// At the end (and on every error) a 0 x 0 image gives the projector back to the scene.
#pragma once

#include <deque>
#include <functional>
#include <string>

#include <opencv2/core.hpp>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Header.h>

namespace rviz_projector
{
struct PatternCaptureOptions
{
  std::string image_topic;    ///< the camera's Image; its CameraInfo is the sibling camera_info topic
  std::string pattern_topic;  ///< the ProjectorCamera's Pattern topic
  double settle = 0.15;       ///< seconds after the acknowledgement before a frame counts
  double ack_timeout = 3.0;   ///< seconds for the projector to acknowledge a pattern
  double frame_timeout = 3.0; ///< seconds for a camera frame after the settle time
};

class PatternCapture
{
public:
  explicit PatternCapture(const PatternCaptureOptions& options);
  ~PatternCapture();  ///< gives the projector back to the scene

  /// Waits until the projector listens on the Pattern topic and the camera's Image and CameraInfo
  /// arrive; "" or what is missing after `timeout` seconds.
  std::string waitUntilReady(double timeout);
  /// The camera's CameraInfo (valid after waitUntilReady).
  const sensor_msgs::CameraInfo& cameraInfo() const { return camera_info_; }
  /// The camera's optical frame (the Image's frame_id, else the CameraInfo's).
  std::string cameraFrame() const;

  /// Shows `pattern` (CV_8UC1, the projector's size) named `name` and captures the camera frame that
  /// sees it, as mono8 into `frame`. Returns "" or the error.
  std::string capture(const cv::Mat& pattern, const std::string& name, cv::Mat& frame);
  /// The scene back on the projector (a 0 x 0 pattern), acknowledged or not within a second.
  void end();

private:
  void onImage(const sensor_msgs::Image::ConstPtr& msg);
  /// Spins this node's callbacks until `done` or `timeout` seconds of wall time; returns done().
  bool spinUntil(const std::function<bool()>& done, double timeout);
  /// A stamp after every earlier one (ROS time; sim time may stand still).
  ros::Time nextStamp();

  PatternCaptureOptions options_;
  ros::NodeHandle nh_;
  ros::Publisher pattern_pub_;
  ros::Subscriber shown_sub_;
  ros::Subscriber image_sub_;
  ros::Subscriber info_sub_;
  std::deque<sensor_msgs::Image::ConstPtr> frames_;  ///< newest last, a few seconds' worth
  sensor_msgs::CameraInfo camera_info_;
  bool has_info_ = false;
  std_msgs::Header last_ack_;
  ros::Time last_ack_received_;
  ros::Time last_stamp_;
  bool ended_ = true;
};
}  // namespace rviz_projector
