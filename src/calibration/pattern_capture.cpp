#include "rviz_projector/calibration/pattern_capture.h"

#include <cv_bridge/cv_bridge.h>
#include <ros/callback_queue.h>
#include <sensor_msgs/image_encodings.h>

namespace rviz_projector
{
namespace
{
/// The sibling camera_info topic of an image topic (image_transport's convention).
std::string infoTopicOf(const std::string& image_topic)
{
  const std::size_t slash = image_topic.rfind('/');
  return slash == std::string::npos ? std::string("camera_info") : image_topic.substr(0, slash + 1) + "camera_info";
}

constexpr std::size_t kMaxFrames = 90;  // 3 s of a 30 fps camera
}  // namespace

PatternCapture::PatternCapture(const PatternCaptureOptions& options) : options_(options)
{
  pattern_pub_ = nh_.advertise<sensor_msgs::Image>(options_.pattern_topic, 2);
  shown_sub_ = nh_.subscribe<std_msgs::Header>(options_.pattern_topic + "/shown", 10,
                                               [this](const std_msgs::Header::ConstPtr& h) {
                                                 last_ack_ = *h;
                                                 last_ack_received_ = ros::Time::now();
                                               });
  image_sub_ = nh_.subscribe(options_.image_topic, 5, &PatternCapture::onImage, this);
  info_sub_ = nh_.subscribe<sensor_msgs::CameraInfo>(infoTopicOf(options_.image_topic), 1,
                                                     [this](const sensor_msgs::CameraInfo::ConstPtr& info) {
                                                       camera_info_ = *info;
                                                       has_info_ = true;
                                                     });
}

PatternCapture::~PatternCapture()
{
  end();
}

void PatternCapture::onImage(const sensor_msgs::Image::ConstPtr& msg)
{
  frames_.push_back(msg);
  while (frames_.size() > kMaxFrames)
  {
    frames_.pop_front();
  }
}

bool PatternCapture::spinUntil(const std::function<bool()>& done, double timeout)
{
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && !done())
  {
    if (ros::WallTime::now() > deadline)
    {
      return false;
    }
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.005));
  }
  return done();
}

std::string PatternCapture::waitUntilReady(double timeout)
{
  if (!spinUntil([this] { return pattern_pub_.getNumSubscribers() > 0; }, timeout))
  {
    return "nothing listens on " + options_.pattern_topic +
           ": is a ProjectorCamera (rviz or projector_host) running with Pattern topic " + options_.pattern_topic +
           "?";
  }
  if (!spinUntil([this] { return shown_sub_.getNumPublishers() > 0; }, timeout))
  {
    return "nothing publishes " + options_.pattern_topic + "/shown: the projector cannot acknowledge patterns";
  }
  if (!spinUntil([this] { return !frames_.empty(); }, timeout))
  {
    return "no image on " + options_.image_topic + " within " + std::to_string(int(timeout)) +
           " s: is the camera running (--image)?";
  }
  if (!spinUntil([this] { return has_info_; }, timeout))
  {
    return "no CameraInfo on " + infoTopicOf(options_.image_topic) + " (the camera's calibration, D included)";
  }
  return std::string();
}

std::string PatternCapture::cameraFrame() const
{
  if (!frames_.empty() && !frames_.back()->header.frame_id.empty())
  {
    return frames_.back()->header.frame_id;
  }
  return camera_info_.header.frame_id;
}

ros::Time PatternCapture::nextStamp()
{
  ros::Time stamp = ros::Time::now();
  if (stamp <= last_stamp_)
  {
    stamp = last_stamp_ + ros::Duration(0, 1000);  // unique even when (simulated) time stands still
  }
  last_stamp_ = stamp;
  return stamp;
}

std::string PatternCapture::capture(const cv::Mat& pattern, const std::string& name, cv::Mat& frame)
{
  if (pattern.empty() || pattern.type() != CV_8UC1)
  {
    return "pattern '" + name + "' is not an 8-bit single-channel image";
  }
  sensor_msgs::Image msg;
  msg.header.stamp = nextStamp();
  msg.header.frame_id = name;
  msg.width = static_cast<std::uint32_t>(pattern.cols);
  msg.height = static_cast<std::uint32_t>(pattern.rows);
  msg.encoding = sensor_msgs::image_encodings::MONO8;
  msg.step = msg.width;
  msg.data.resize(std::size_t(msg.step) * msg.height);
  for (int row = 0; row < pattern.rows; ++row)
  {
    std::copy(pattern.ptr<std::uint8_t>(row), pattern.ptr<std::uint8_t>(row) + pattern.cols,
              msg.data.begin() + std::ptrdiff_t(row) * msg.step);
  }
  const ros::Time stamp = msg.header.stamp;
  ended_ = false;
  pattern_pub_.publish(msg);
  if (!spinUntil([&] { return last_ack_.stamp == stamp && last_ack_.frame_id == name; }, options_.ack_timeout))
  {
    return "the projector did not acknowledge '" + name + "' on " + options_.pattern_topic + "/shown within " +
           std::to_string(options_.ack_timeout).substr(0, 3) +
           " s (a Pattern error in the ProjectorCamera's statuses says why, e.g. a size that is not the "
           "projector's)";
  }
  // Only a frame exposed after the pattern was on the floor: stamped at or after ack + settle.
  const ros::Time earliest = last_ack_received_ + ros::Duration(options_.settle);
  sensor_msgs::Image::ConstPtr chosen;
  const bool got = spinUntil(
      [&] {
        for (const auto& f : frames_)
        {
          if (f->header.stamp >= earliest)
          {
            chosen = f;
            return true;
          }
        }
        return false;
      },
      options_.settle * 4.0 + options_.frame_timeout);
  if (!got)
  {
    return "no camera frame on " + options_.image_topic + " stamped after '" + name +
           "' was on screen (+ settle): is the camera still publishing, with stamps of this ROS clock?";
  }
  try
  {
    frame = cv_bridge::toCvCopy(chosen, sensor_msgs::image_encodings::MONO8)->image;
  }
  catch (const cv_bridge::Exception& e)
  {
    return "camera image '" + chosen->encoding + "' cannot be turned into grey levels: " + e.what();
  }
  frames_.clear();  // the next pattern needs newer frames anyway
  return std::string();
}

void PatternCapture::end()
{
  if (ended_)
  {
    return;
  }
  ended_ = true;
  sensor_msgs::Image scene;  // 0 x 0: the scene comes back
  scene.header.stamp = nextStamp();
  scene.header.frame_id = "end of calibration";
  pattern_pub_.publish(scene);
  const ros::Time stamp = scene.header.stamp;
  spinUntil([&] { return last_ack_.stamp == stamp; }, 1.0);
}
}  // namespace rviz_projector
