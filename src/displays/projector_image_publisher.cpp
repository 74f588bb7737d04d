#include "rviz_projector/displays/projector_image_publisher.h"

#include <algorithm>

#include "rviz_projector/core/lens_view.h"
#include "rviz_projector/displays/render_target_readback.h"

namespace rviz_projector
{
sensor_msgs::CameraInfo cameraInfoOfImage(const PinholeModel& lens, const PixelRect& rect,
                                          const std_msgs::Header& header, const LensDistortion& distortion)
{
  const PinholeModel shown =
      scaledLens(lens, static_cast<std::uint32_t>(std::max(0, rect.width)), static_cast<std::uint32_t>(std::max(0, rect.height)));
  sensor_msgs::CameraInfo info;
  info.header = header;
  info.width = shown.width();
  info.height = shown.height();
  // What the renderer drew: the ideal pinhole, or through the lens's D (normalised coordinates: the
  // same D at any scale). A model it cannot draw was ignored: no distortion.
  info.distortion_model = distortion.none() ? "plumb_bob" : modelName(distortion.model());
  info.D = distortion.none() ? std::vector<double>(5, 0.0) : distortion.coefficients();
  info.K = {shown.fx(), 0.0, shown.cx(), 0.0, shown.fy(), shown.cy(), 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {shown.fx(), 0.0, shown.cx(), shown.tx(), 0.0, shown.fy(), shown.cy(), shown.ty(), 0.0, 0.0, 1.0, 0.0};
  info.binning_x = 0;
  info.binning_y = 0;
  info.roi = sensor_msgs::RegionOfInterest();  // all zero: the full image
  return info;
}

std::string ProjectorImagePublisher::start(ros::NodeHandle& nh, const std::string& image_topic, double rate)
{
  stop();
  period_ = rate > 0.0 ? 1.0 / rate : 0.1;
  try
  {
    image_pub_ = nh.advertise<sensor_msgs::Image>(image_topic, 1);
    const std::string::size_type slash = image_topic.rfind('/');
    const std::string prefix = slash == std::string::npos ? std::string() : image_topic.substr(0, slash + 1);
    info_pub_ = nh.advertise<sensor_msgs::CameraInfo>(prefix + "camera_info", 1);
  }
  catch (const ros::Exception& e)
  {
    stop();
    return e.what();
  }
  return std::string();
}

void ProjectorImagePublisher::stop()
{
  image_pub_.shutdown();
  info_pub_.shutdown();
  image_pub_ = ros::Publisher();
  info_pub_ = ros::Publisher();
}

bool ProjectorImagePublisher::due() const
{
  return active() && (ros::WallTime::now() - last_).toSec() >= period_;
}

bool ProjectorImagePublisher::publish(Ogre::RenderTarget* target, const PixelRect& rect, const PinholeModel& lens,
                                      const LensDistortion& distortion, const std::string& frame, const ros::Time& stamp)
{
  last_ = ros::WallTime::now();
  unsigned ww = 0, wh = 0;
  if (!readRgbPixels(target, buffer_, ww, wh) || rect.width <= 0 || rect.height <= 0 || rect.left < 0 ||
      rect.top < 0 || static_cast<unsigned>(rect.left + rect.width) > ww ||
      static_cast<unsigned>(rect.top + rect.height) > wh)
  {
    return false;
  }
  image_.header.stamp = stamp;
  image_.header.frame_id = frame;
  image_.width = static_cast<std::uint32_t>(rect.width);
  image_.height = static_cast<std::uint32_t>(rect.height);
  image_.encoding = "rgb8";
  image_.step = image_.width * 3;
  image_.data.resize(static_cast<std::size_t>(image_.step) * image_.height);
  for (int row = 0; row < rect.height; ++row)
  {
    const std::uint8_t* src =
        buffer_.data() + (static_cast<std::size_t>(row + rect.top) * ww + static_cast<std::size_t>(rect.left)) * 3;
    std::copy(src, src + image_.step, image_.data.begin() + static_cast<std::ptrdiff_t>(row) * image_.step);
  }
  image_pub_.publish(image_);
  if (lens.width() > 0)
  {
    info_pub_.publish(cameraInfoOfImage(lens, rect, image_.header, distortion));
  }
  return true;
}
}  // namespace rviz_projector
