// One part of ProjectorCameraDisplay: the optional Image output. Publishes the rendered projector
// image (the image area of the output window, as the floor gets it) as sensor_msgs/Image, with a
// CameraInfo that describes exactly that image: image_geometry on the published pair projects a
// point to where it appears in the published image.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "rviz_projector/core/letterbox.h"
#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"

namespace Ogre
{
class RenderTarget;
}

namespace rviz_projector
{
/// The CameraInfo of an image of `rect`'s size showing `lens`'s view (scaled, no binning, no region
/// of interest) through `distortion` (the warp draws it: its D, unchanged by scaling, in the message).
sensor_msgs::CameraInfo cameraInfoOfImage(const PinholeModel& lens, const PixelRect& rect,
                                          const std_msgs::Header& header,
                                          const LensDistortion& distortion = LensDistortion());

class ProjectorImagePublisher
{
public:
  /// Advertises `image_topic` and camera_info beside it; returns an error text (empty: fine).
  std::string start(ros::NodeHandle& nh, const std::string& image_topic, double rate);
  void stop();
  bool active() const { return static_cast<bool>(image_pub_); }
  /// Whether the next image is due (the rate since the last one has passed).
  bool due() const;
  /// Reads the back buffer of `target` (rendered, not yet swapped), crops `rect` and publishes it
  /// with its CameraInfo. Returns false when nothing could be read.
  /// `stamp`: the time of the pose the image was rendered for (the prediction's target time when
  /// motion compensation predicted, else the pose's tf stamp; ROS now for a static pose).
  bool publish(Ogre::RenderTarget* target, const PixelRect& rect, const PinholeModel& lens,
               const LensDistortion& distortion, const std::string& frame, const ros::Time& stamp);

private:
  ros::Publisher image_pub_;
  ros::Publisher info_pub_;
  double period_ = 0.1;
  ros::WallTime last_;
  std::vector<std::uint8_t> buffer_;
  sensor_msgs::Image image_;
};
}  // namespace rviz_projector
