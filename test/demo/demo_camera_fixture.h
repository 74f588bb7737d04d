// The demo_camera test's oracle and harness (test/demo/demo_camera_test.cpp): the parameters read
// back from the parameter server, the forward chain projector pixel -> floor -> camera pixel (tf2
// rotations, cv::projectPoints; no code shared with the node), the node seen from outside (its
// frames, CameraInfo, tf and /rosout warnings; the projector image publisher), synthetic projector
// images and the measurements on camera frames (centroid, peak, window mean, edge crossing).
#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include <cmath>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>


namespace demo_camera_test
{
const std::string kNode = "/demo_camera";
const char* const kProjectorTopic = "/test_projector/image";
constexpr int kProjectorWidth = 1280;
constexpr int kProjectorHeight = 800;
constexpr std::size_t kFramesKept = 150;

inline double param(const std::string& name)
{
  double value = std::nan("");
  EXPECT_TRUE(ros::param::get(kNode + "/" + name, value)) << name;
  return value;
}

inline std::vector<double> listParam(const std::string& name)
{
  std::vector<double> value;
  EXPECT_TRUE(ros::param::get(kNode + "/" + name, value)) << name;
  return value;
}

struct Mount
{
  double x, y, z, roll, pitch, yaw;
};

inline Mount mountParams(const std::string& prefix)
{
  return Mount{param(prefix + "x"),    param(prefix + "y"),     param(prefix + "z"),
               param(prefix + "roll"), param(prefix + "pitch"), param(prefix + "yaw")};
}

/// Orientation of the optical frame in base_link, by tf2: setRPY, then projector.launch's
/// body -> optical quaternion.
inline tf2::Quaternion opticalQuaternion(const Mount& m)
{
  tf2::Quaternion body;
  body.setRPY(m.roll, m.pitch, m.yaw);
  return body * tf2::Quaternion(-0.5, 0.5, -0.5, 0.5);
}

inline cv::Matx33d matrixOf(const tf2::Quaternion& q)
{
  const tf2::Matrix3x3 m(q);
  return cv::Matx33d(m[0][0], m[0][1], m[0][2], m[1][0], m[1][1], m[1][2], m[2][0], m[2][1], m[2][2]);
}

/// The forward chain: projector pixel -> floor -> camera pixel.
struct Oracle
{
  Oracle()
  {
    const Mount camera = mountParams("");
    const cv::Matx33d camera_r = matrixOf(opticalQuaternion(camera));
    const cv::Matx33d world_to_camera = camera_r.t();
    cv::Rodrigues(cv::Mat(world_to_camera), rvec);
    tvec = -(world_to_camera * cv::Vec3d(camera.x, camera.y, camera.z));
    camera_k = cv::Matx33d(param("fx"), 0.0, param("cx"), 0.0, param("fy"), param("cy"), 0.0, 0.0, 1.0);
    camera_d = listParam("D");
    const Mount projector = mountParams("projector_");
    projector_r = matrixOf(opticalQuaternion(projector));
    projector_c = cv::Vec3d(projector.x, projector.y, projector.z);
    pfx = param("projector_fx");
    pfy = param("projector_fy");
    pcx = param("projector_cx");
    pcy = param("projector_cy");
    for (double d : listParam("projector_D"))
    {
      EXPECT_EQ(d, 0.0) << "the oracle's projector is a pinhole";
    }
    ambient = 255.0 * param("ambient");
    gain = param("gain");
    noise = 255.0 * param("noise");
    delay = param("exposure_delay");
  }

  cv::Point2d cameraPixel(const cv::Point2d& projector_pixel) const
  {
    const cv::Vec3d ray =
        projector_r * cv::Vec3d((projector_pixel.x - pcx) / pfx, (projector_pixel.y - pcy) / pfy, 1.0);
    const double t = -projector_c[2] / ray[2];
    const cv::Vec3d floor = projector_c + t * ray;
    std::vector<cv::Point2d> pixels;
    cv::projectPoints(std::vector<cv::Point3d>{cv::Point3d(floor[0], floor[1], floor[2])}, rvec, tvec, camera_k,
                      camera_d, pixels);
    return pixels.at(0);
  }

  /// A window of camera pixels around where the projector pixel lands.
  cv::Rect windowAround(const cv::Point2d& projector_pixel, int half) const
  {
    const cv::Point2d c = cameraPixel(projector_pixel);
    return cv::Rect(static_cast<int>(std::lround(c.x)) - half, static_cast<int>(std::lround(c.y)) - half, 2 * half + 1,
                    2 * half + 1);
  }

  cv::Vec3d rvec, tvec;
  cv::Matx33d camera_k;
  std::vector<double> camera_d;
  cv::Matx33d projector_r;
  cv::Vec3d projector_c;
  double pfx = 0, pfy = 0, pcx = 0, pcy = 0;
  double ambient = 0, gain = 0, noise = 0, delay = 0;
};

struct Frame
{
  ros::Time stamp;
  cv::Mat image;  // CV_8UC1
};

inline double meanOf(const Frame& frame, const cv::Rect& rect)
{
  return cv::mean(frame.image(rect))[0];
}

/// The node under test seen from outside: its frames, CameraInfo and log; the projector publisher.
class Harness
{
public:
  Harness() : listener_(buffer_), spinner_(2)
  {
    frame_sub_ = nh_.subscribe(kNode + "/image_raw", 10, &Harness::onFrame, this);
    info_sub_ = nh_.subscribe(kNode + "/camera_info", 10, &Harness::onInfo, this);
    log_sub_ = nh_.subscribe("/rosout", 100, &Harness::onLog, this);
    projector_pub_ = nh_.advertise<sensor_msgs::Image>(kProjectorTopic, 10);
    spinner_.start();
  }
  /// The spinner's threads first: a frame arriving during destruction must not reach frames_.
  ~Harness()
  {
    spinner_.stop();
    frame_sub_.shutdown();
    info_sub_.shutdown();
    log_sub_.shutdown();
  }
  Harness(const Harness&) = delete;
  Harness& operator=(const Harness&) = delete;

  static bool waitFor(const std::function<bool()>& condition, double timeout)
  {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline)
    {
      if (condition())
      {
        return true;
      }
      ros::WallDuration(0.005).sleep();
    }
    return condition();
  }

  /// Frames stamped after `after`, oldest first.
  std::vector<Frame> framesAfter(const ros::Time& after)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Frame> result;
    for (const Frame& frame : frames_)
    {
      if (frame.stamp > after)
      {
        result.push_back(frame);
      }
    }
    return result;
  }

  /// The first frame stamped after `after` that satisfies `test` (within `timeout` s of wall time).
  bool waitForFrame(const ros::Time& after, const std::function<bool(const Frame&)>& test, Frame& found,
                    double timeout = 15.0)
  {
    return waitFor(
        [&] {
          for (const Frame& frame : framesAfter(after))
          {
            if (test(frame))
            {
              found = frame;
              return true;
            }
          }
          return false;
        },
        timeout);
  }

  /// Publishes a projector image; returns the ROS time taken just before.
  ros::Time publish(const sensor_msgs::Image& image)
  {
    EXPECT_TRUE(waitFor([this] { return projector_pub_.getNumSubscribers() > 0; }, 15.0));
    const ros::Time before = ros::Time::now();
    projector_pub_.publish(image);
    return before;
  }

  bool latestInfo(sensor_msgs::CameraInfo& info)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (infos_ == 0)
    {
      return false;
    }
    info = info_;
    return true;
  }

  bool warned(const std::string& text)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (const rosgraph_msgs::Log& log : logs_)
    {
      if (log.name == kNode && log.level == rosgraph_msgs::Log::WARN && log.msg.find(text) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }

  /// `first` and the frames after it, `count` in all (waits for them).
  std::vector<Frame> framesFrom(const Frame& first, std::size_t count)
  {
    std::vector<Frame> frames{first};
    EXPECT_TRUE(waitFor([&] { return framesAfter(first.stamp).size() + 1 >= count; }, 15.0));
    for (const Frame& frame : framesAfter(first.stamp))
    {
      if (frames.size() < count)
      {
        frames.push_back(frame);
      }
    }
    return frames;
  }

  int badFrames() const { return bad_frames_; }
  tf2_ros::Buffer& buffer() { return buffer_; }

private:
  void onFrame(const sensor_msgs::ImageConstPtr& msg)
  {
    if (msg->encoding != "mono8" || msg->step != msg->width || msg->data.size() != msg->step * msg->height)
    {
      ++bad_frames_;
      return;
    }
    Frame frame;
    frame.stamp = msg->header.stamp;
    frame.image = cv::Mat(static_cast<int>(msg->height), static_cast<int>(msg->width), CV_8UC1,
                          const_cast<std::uint8_t*>(msg->data.data()))
                      .clone();
    std::lock_guard<std::mutex> lock(mutex_);
    frames_.push_back(frame);
    while (frames_.size() > kFramesKept)
    {
      frames_.pop_front();
    }
  }

  void onInfo(const sensor_msgs::CameraInfoConstPtr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    info_ = *msg;
    ++infos_;
  }

  void onLog(const rosgraph_msgs::LogConstPtr& msg)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    logs_.push_back(*msg);
  }

  ros::NodeHandle nh_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  ros::AsyncSpinner spinner_;
  ros::Subscriber frame_sub_;
  ros::Subscriber info_sub_;
  ros::Subscriber log_sub_;
  ros::Publisher projector_pub_;
  std::mutex mutex_;
  std::deque<Frame> frames_;
  sensor_msgs::CameraInfo info_;
  int infos_ = 0;
  std::vector<rosgraph_msgs::Log> logs_;
  int bad_frames_ = 0;
};


inline sensor_msgs::Image projectorImage(const std::string& encoding, const std::vector<std::uint8_t>& pixel)
{
  sensor_msgs::Image image;
  image.encoding = encoding;
  image.width = kProjectorWidth;
  image.height = kProjectorHeight;
  image.step = static_cast<std::uint32_t>(kProjectorWidth * pixel.size());
  image.data.resize(image.step * image.height);
  for (std::size_t i = 0; i < image.data.size(); ++i)
  {
    image.data[i] = pixel[i % pixel.size()];
  }
  return image;
}

/// Black, with a 21 x 21 white square centred on projector pixel (u, v).
inline sensor_msgs::Image blobImage(int u, int v)
{
  sensor_msgs::Image image = projectorImage("mono8", {0});
  for (int row = v - 10; row <= v + 10; ++row)
  {
    for (int col = u - 10; col <= u + 10; ++col)
    {
      image.data[static_cast<std::size_t>(row) * image.step + static_cast<std::size_t>(col)] = 255;
    }
  }
  return image;
}

/// Intensity centroid in `window`, above the mean of the window's one-pixel border.
inline cv::Point2d centroid(const Frame& frame, const cv::Rect& window)
{
  double border = 0.0;
  int border_count = 0;
  for (int y = window.y; y < window.y + window.height; ++y)
  {
    for (int x = window.x; x < window.x + window.width; ++x)
    {
      if (y == window.y || x == window.x || y == window.y + window.height - 1 || x == window.x + window.width - 1)
      {
        border += frame.image.at<std::uint8_t>(y, x);
        ++border_count;
      }
    }
  }
  border /= border_count;
  double sum = 0.0, sx = 0.0, sy = 0.0;
  for (int y = window.y; y < window.y + window.height; ++y)
  {
    for (int x = window.x; x < window.x + window.width; ++x)
    {
      const double w = frame.image.at<std::uint8_t>(y, x) - border;
      sum += w;
      sx += w * x;
      sy += w * y;
    }
  }
  return cv::Point2d(sx / sum, sy / sum);
}

inline double peak(const Frame& frame, const cv::Rect& window)
{
  double max = 0.0;
  cv::minMaxLoc(frame.image(window), nullptr, &max);
  return max;
}

/// Shows image `expected` (a projector image that is uniform near the centre): the mean of a
/// window around the projector's centre is that level.
inline bool interiorNear(const Oracle& oracle, const Frame& frame, double level, double tolerance)
{
  const cv::Rect interior = oracle.windowAround(cv::Point2d(640, 400), 20);
  return std::abs(meanOf(frame, interior) - level) < tolerance;
}

/// Sub-pixel position where the profile from `inside` to `outside` (camera pixels along one row or
/// column of `frame`) first drops below `level`; NaN if it never does.
inline double crossing(const Frame& frame, bool along_column, int line, int inside, int outside, double level)
{
  const int step = outside > inside ? 1 : -1;
  auto at = [&](int i) {
    return static_cast<double>(along_column ? frame.image.at<std::uint8_t>(i, line)
                                            : frame.image.at<std::uint8_t>(line, i));
  };
  for (int i = inside; i != outside; i += step)
  {
    const double a = at(i), b = at(i + step);
    if (a >= level && b < level)
    {
      return i + step * (a - level) / (a - b);
    }
  }
  return std::nan("");
}

}  // namespace demo_camera_test
