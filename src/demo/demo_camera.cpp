// demo_camera: a simulated camera on the demo robot that sees the floor lit by the projector (issue
// 24 part 3), for the demo and the tests of the camera-based projector calibration. Not for a robot.
//
// It watches what the projector shows (the ProjectorCamera display's rendered image) and publishes
// what a camera on the robot would see of the floor: the projector's light where it falls according
// to the TRUE projector mount and lens given here -- which the calibration the display uses may get
// wrong (that is the point: the demo starts with a wrong mount and calibrates). The geometry is
// CameraSimulation (camera_simulation.h, written independently of the project's core).
//
// Topics:  ~projector_image (/projector/rendered/image) sensor_msgs/Image in: mono8, rgb8, bgr8,
//          rgba8 or bgra8 (luminance 0.299 R + 0.587 G + 0.114 B); anything else, a zero size or a
//          data size that does not match is refused with a ROS_WARN naming it (each distinct reason
//          at most every 5 s), and the camera goes on showing the last good image.
//          ~image_raw   sensor_msgs/Image out, mono8, at ~rate (ROS time), frame ~frame_id.
//          ~camera_info sensor_msgs/CameraInfo out with each frame (same stamp): K, D (plumb_bob, or
//                       rational_polynomial for 8 values), R = identity, P = [K | 0].
// tf:      static ~base_frame -> ~body_frame (the camera mount: x y z roll pitch yaw as projector.launch
//          takes a projector's) -> ~frame_id (the standard body -> optical rotation).
// Timing:  a frame stamped t shows the projector image that had arrived (ROS time of the callback) at
//          or before t - ~exposure_delay; before any image (or before the first is that old) the
//          floor has ambient light only. ROS time throughout (use_sim_time works): frames are paced
//          by RosTimeScheduler (ros_time_scheduler.h). Time jumping back (a bag loop) keeps the newest
//          image only and shows it at once.
//
// Parameters (defaults):
//   ~rate 30 Hz, ~frame_id demo_camera_optical, ~body_frame demo_camera_link, ~base_frame base_link
//   The camera: ~width 640, ~height 480, ~fx 540, ~fy 540, ~cx 319.5, ~cy 239.5,
//     ~D [-0.1, 0.02, 0, 0, 0] (a mild barrel lens), mount ~x 0.0, ~y 0.0, ~z 1.4, ~roll 0,
//     ~pitch 0.86, ~yaw 0 (a mast 1.4 m high above base_link, 0.15 m behind the projector).
//     Why: the demo projector (launch/demo.launch: 1.2 m up, 0.15 m ahead, pitch 0.876 rad,
//     config/demo_projector.yaml 1280x800, fx = fy = 1300) lights a trapezoid on the floor from
//     0.65 m ahead of base_link (1.22 m wide) to 1.99 m ahead (2.07 m wide). Through this camera
//     its corners fall at (89, 107), (550, 107), (537, 388), (102, 388) pixels: 88 to 104 pixels of
//     margin on every side, the whole patch in view, 2.3 px per cm at its far edge.
//   The TRUE projector: ~projector_x 0.15, ~projector_y 0, ~projector_z 1.2, ~projector_roll 0,
//     ~projector_pitch 0.8760580505981934, ~projector_yaw 0; ~projector_fx 1300, ~projector_fy 1300,
//     ~projector_cx 639.5, ~projector_cy 399.5, ~projector_D [] (none). Its image size is the
//     received image's: the lens is that image's lens.
//   ~ambient 0.2 (floor brightness without projector light, 0..1), ~gain 0.7 (what a white projector
//   pixel adds, 0..10; ambient + gain above 1 saturates), ~blur 1.0 (Gaussian sigma,
//   pixels), ~noise 0.00784 (= 2/255, Gaussian sigma in grey levels / 255), ~seed 1 (of the noise),
//   ~supersampling 3 (sub-pixels per pixel and axis), ~exposure_delay 0.05 s (0..2).
//   A checkerboard for calibrate_projector --board (default none): ~board_pose [x, y, z, roll, pitch,
//     yaw] of its centre in ~base_frame (roll = pitch = yaw = 0 lies face up; pitch -0.785 stands
//     45 deg facing the robot), ~board_corners [7, 5] (inner corners), ~board_square 0.06 m,
//     ~board_margin 0.03 m (white around the squares); see camera_simulation.h.
//   A parameter that does not make sense stops the node with a ROS_FATAL saying which.
// Cost (2-core VM, defaults, 1280x800 rgb8 projector images at 30 Hz): about 40 % of a core when
// every image differs (one remap of the lit part of the 1920x1440 sub-pixel grid, ~8 ms), about
// 15 % when they repeat (an image equal to the previous one shares its pixels and its rendering:
// calibration patterns are held for several frames), 8 % without projector images. The maps
// take about a second to build, once per projector image size.

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "camera_simulation.h"
#include "ros_time_scheduler.h"

#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace
{
using namespace rviz_projector_demo;

constexpr double kWarnPeriod = 5.0;   // s of wall time between two warnings of the same reason
constexpr double kMaxExposureDelay = 2.0;
constexpr double kMaxResidual = 0.01;  // px: the camera lens' undistortion must be this exact

struct Options
{
  CameraSimulationSettings simulation;
  std::string projector_image;
  std::string frame_id;
  std::string body_frame;
  std::string base_frame;
  double rate = 30.0;
  double exposure_delay = 0.05;
  int seed = 1;
};

// Reads private parameters; a parameter that is set but of the wrong type is a problem (never the
// default in silence).
class ParamReader
{
public:
  explicit ParamReader(const ros::NodeHandle& pnh) : pnh_(pnh) {}

  template <typename T>
  T param(const std::string& name, const T& fallback)
  {
    T value = fallback;
    if (pnh_.hasParam(name) && !pnh_.getParam(name, value))
    {
      problems_ += "~" + name + " has the wrong type. ";
      value = fallback;
    }
    return value;
  }
  const std::string& problems() const { return problems_; }

private:
  ros::NodeHandle pnh_;
  std::string problems_;
};

Options readOptions(const ros::NodeHandle& pnh, std::string& problems)
{
  ParamReader p(pnh);
  Options o;
  CameraSimulationSettings& s = o.simulation;
  o.projector_image = p.param<std::string>("projector_image", "/projector/rendered/image");
  o.frame_id = p.param<std::string>("frame_id", "demo_camera_optical");
  o.body_frame = p.param<std::string>("body_frame", "demo_camera_link");
  o.base_frame = p.param<std::string>("base_frame", "base_link");
  o.rate = p.param("rate", 30.0);
  o.exposure_delay = p.param("exposure_delay", 0.05);
  o.seed = p.param("seed", 1);

  s.width = p.param("width", 640);
  s.height = p.param("height", 480);
  s.camera.fx = p.param("fx", 540.0);
  s.camera.fy = p.param("fy", 540.0);
  s.camera.cx = p.param("cx", 319.5);
  s.camera.cy = p.param("cy", 239.5);
  s.camera.D = p.param("D", std::vector<double>{-0.1, 0.02, 0.0, 0.0, 0.0});
  s.camera_mount.x = p.param("x", 0.0);
  s.camera_mount.y = p.param("y", 0.0);
  s.camera_mount.z = p.param("z", 1.4);
  s.camera_mount.roll = p.param("roll", 0.0);
  s.camera_mount.pitch = p.param("pitch", 0.86);
  s.camera_mount.yaw = p.param("yaw", 0.0);

  s.projector.fx = p.param("projector_fx", 1300.0);
  s.projector.fy = p.param("projector_fy", 1300.0);
  s.projector.cx = p.param("projector_cx", 639.5);
  s.projector.cy = p.param("projector_cy", 399.5);
  s.projector.D = p.param("projector_D", std::vector<double>{});
  s.projector_mount.x = p.param("projector_x", 0.15);
  s.projector_mount.y = p.param("projector_y", 0.0);
  s.projector_mount.z = p.param("projector_z", 1.2);
  s.projector_mount.roll = p.param("projector_roll", 0.0);
  s.projector_mount.pitch = p.param("projector_pitch", 0.8760580505981934);
  s.projector_mount.yaw = p.param("projector_yaw", 0.0);

  s.supersampling = p.param("supersampling", 3);
  s.ambient = p.param("ambient", 0.2);
  s.gain = p.param("gain", 0.7);
  s.blur = p.param("blur", 1.0);
  s.noise = p.param("noise", 2.0 / 255.0);
  const std::vector<double> board_pose = p.param("board_pose", std::vector<double>{});
  const std::vector<int> board_corners = p.param("board_corners", std::vector<int>{7, 5});
  s.board.square = p.param("board_square", 0.06);
  s.board.margin = p.param("board_margin", 0.03);
  problems = p.problems();
  if (!board_pose.empty())
  {
    if (board_pose.size() != 6 || board_corners.size() != 2)
    {
      problems += "~board_pose must be [x, y, z, roll, pitch, yaw] and ~board_corners [cols, rows]. ";
    }
    else
    {
      s.board.present = true;
      s.board.pose = MountPose{board_pose[0], board_pose[1], board_pose[2], board_pose[3], board_pose[4], board_pose[5]};
      s.board.cols = board_corners[0];
      s.board.rows = board_corners[1];
    }
  }
  return o;
}

std::string checkOptions(const Options& o, std::string problems)
{
  const std::string settings = checkSettings(o.simulation);
  if (!settings.empty())
  {
    problems += settings + " ";
  }
  auto add = [&problems](const std::string& text) { problems += text + " "; };
  if (!std::isfinite(o.rate) || !(o.rate > 0.0) || o.rate > 1000.0)
  {
    add("~rate must be in (0, 1000] Hz (" + std::to_string(o.rate) + ").");
  }
  if (!std::isfinite(o.exposure_delay) || o.exposure_delay < 0.0 || o.exposure_delay > kMaxExposureDelay)
  {
    add("~exposure_delay must be in [0, 2] s (" + std::to_string(o.exposure_delay) + ").");
  }
  if (o.frame_id.empty() || o.body_frame.empty() || o.base_frame.empty())
  {
    add("~frame_id, ~body_frame and ~base_frame must not be empty.");
  }
  if (!problems.empty())
  {
    problems.pop_back();
  }
  return problems;
}

class DemoCamera
{
public:
  DemoCamera(const ros::NodeHandle& nh, const ros::NodeHandle& pnh, const Options& options)
    : nh_(nh),
      pnh_(pnh),
      options_(options),
      simulation_(options.simulation),
      rng_(static_cast<std::uint64_t>(options.seed)),
      scheduler_("demo_camera")
  {
    image_pub_ = pnh_.advertise<sensor_msgs::Image>("image_raw", 2);
    info_pub_ = pnh_.advertise<sensor_msgs::CameraInfo>("camera_info", 2);
    publishMount();
    info_ = makeCameraInfo();
    projector_sub_ = nh_.subscribe(options_.projector_image, 5, &DemoCamera::onProjectorImage, this,
                                   ros::TransportHints().tcpNoDelay());
    scheduler_.add(1.0 / options_.rate, [this] { publishFrame(); });
    scheduler_.start(nh_);
    const CameraSimulationSettings& s = options_.simulation;
    ROS_INFO("demo_camera: %dx%d at %.1f Hz on %s, watching %s (true projector at x=%.3f y=%.3f z=%.3f, "
             "pitch %.4f rad), exposure delay %.3f s",
             s.width, s.height, options_.rate, image_pub_.getTopic().c_str(), options_.projector_image.c_str(),
             s.projector_mount.x, s.projector_mount.y, s.projector_mount.z, s.projector_mount.pitch,
             options_.exposure_delay);
  }

  bool failed() const { return failed_; }

private:
  void publishMount()
  {
    const MountPose& m = options_.simulation.camera_mount;
    const ros::Time now = ros::Time::now();
    std::vector<geometry_msgs::TransformStamped> transforms(2);
    tf2::Quaternion mount;
    mount.setRPY(m.roll, m.pitch, m.yaw);
    transforms[0].header.stamp = now;
    transforms[0].header.frame_id = options_.base_frame;
    transforms[0].child_frame_id = options_.body_frame;
    transforms[0].transform.translation.x = m.x;
    transforms[0].transform.translation.y = m.y;
    transforms[0].transform.translation.z = m.z;
    transforms[0].transform.rotation.x = mount.x();
    transforms[0].transform.rotation.y = mount.y();
    transforms[0].transform.rotation.z = mount.z();
    transforms[0].transform.rotation.w = mount.w();
    // Body (x forward, y left, z up) -> optical (z forward, x right, y down), as projector.launch.
    transforms[1].header.stamp = now;
    transforms[1].header.frame_id = options_.body_frame;
    transforms[1].child_frame_id = options_.frame_id;
    transforms[1].transform.rotation.x = -0.5;
    transforms[1].transform.rotation.y = 0.5;
    transforms[1].transform.rotation.z = -0.5;
    transforms[1].transform.rotation.w = 0.5;
    static_broadcaster_.sendTransform(transforms);
  }

  sensor_msgs::CameraInfo makeCameraInfo() const
  {
    const CameraSimulationSettings& s = options_.simulation;
    sensor_msgs::CameraInfo info;
    info.header.frame_id = options_.frame_id;
    info.width = static_cast<std::uint32_t>(s.width);
    info.height = static_cast<std::uint32_t>(s.height);
    info.D = s.camera.D;
    if (info.D.size() == 8)
    {
      info.distortion_model = "rational_polynomial";
    }
    else
    {
      info.distortion_model = "plumb_bob";
      info.D.resize(5, 0.0);  // none or k1 k2 p1 p2: k3 = 0
    }
    info.K = {s.camera.fx, 0.0, s.camera.cx, 0.0, s.camera.fy, s.camera.cy, 0.0, 0.0, 1.0};
    info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    info.P = {s.camera.fx, 0.0, s.camera.cx, 0.0, 0.0, s.camera.fy, s.camera.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
    return info;
  }

  void onProjectorImage(const sensor_msgs::ImageConstPtr& msg)
  {
    const ros::Time arrival = ros::Time::now();
    cv::Mat luminance;
    const std::string why =
        projectorLuminance(msg->encoding, static_cast<int>(std::min<std::uint32_t>(msg->width, 1u << 30)),
                           static_cast<int>(std::min<std::uint32_t>(msg->height, 1u << 30)), msg->step,
                           msg->data.data(), msg->data.size(), luminance);
    if (!why.empty())
    {
      warnThrottled("demo_camera: ignoring a projector image on " + options_.projector_image + ": " + why +
                    " (still showing the last good one)");
      return;
    }
    // The same picture again (a calibration pattern held for several frames, a still scene) shares
    // the previous one's pixels: the frames that show it need no new rendering.
    const ExposureHistory::Entry* newest = history_.newest();
    if (newest != nullptr && newest->luminance.size() == luminance.size() &&
        cv::norm(newest->luminance, luminance, cv::NORM_INF) == 0.0)
    {
      luminance = newest->luminance;
    }
    history_.add(arrival.toSec(), luminance);
  }

  void warnThrottled(const std::string& text)
  {
    const ros::WallTime now = ros::WallTime::now();
    auto it = last_warning_.find(text);
    if (it != last_warning_.end() && (now - it->second).toSec() < kWarnPeriod)
    {
      return;
    }
    last_warning_[text] = now;
    ROS_WARN("%s", text.c_str());
  }

  void publishFrame()
  {
    const ros::Time now = ros::Time::now();
    if (!last_frame_.isZero() && now < last_frame_)
    {
      history_.restart();
    }
    last_frame_ = now;
    const ExposureHistory::Entry* entry = history_.at(now.toSec() - options_.exposure_delay);
    const cv::Mat source = entry != nullptr ? entry->luminance : cv::Mat();
    if (clean_.empty() || source.data != clean_source_.data)
    {
      const cv::Size before = projector_size_;
      clean_ = simulation_.renderClean(source);
      clean_source_ = source;  // held: its pixels cannot be freed and their address reused
      if (entry != nullptr && entry->luminance.size() != before)
      {
        projector_size_ = entry->luminance.size();
        reportMaps();
      }
    }
    const cv::Mat frame = simulation_.expose(clean_, rng_);

    sensor_msgs::Image image;
    image.header.stamp = now;
    image.header.frame_id = options_.frame_id;
    image.width = static_cast<std::uint32_t>(frame.cols);
    image.height = static_cast<std::uint32_t>(frame.rows);
    image.encoding = "mono8";
    image.step = static_cast<std::uint32_t>(frame.cols);
    image.data.resize(static_cast<std::size_t>(frame.cols) * static_cast<std::size_t>(frame.rows));
    for (int row = 0; row < frame.rows; ++row)
    {
      std::memcpy(&image.data[static_cast<std::size_t>(row) * image.step], frame.ptr<std::uint8_t>(row), image.step);
    }
    info_.header.stamp = now;
    image_pub_.publish(image);
    info_pub_.publish(info_);
  }

  void reportMaps()
  {
    const double residual = simulation_.undistortionResidual();
    ROS_INFO("demo_camera: projector image %dx%d: %.1f %% of the camera's view is lit; camera lens undistorted "
             "to %.2g px",
             projector_size_.width, projector_size_.height, 100.0 * simulation_.litFraction(), residual);
    if (residual > kMaxResidual)
    {
      ROS_FATAL("demo_camera: the camera lens (~D) cannot be undistorted to %.2g px (%.3g px): the simulated "
                "image would be wrong; stopping",
                kMaxResidual, residual);
      failed_ = true;
      ros::shutdown();
    }
  }

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  Options options_;
  CameraSimulation simulation_;
  ExposureHistory history_;
  cv::RNG rng_;
  RosTimeScheduler scheduler_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  ros::Publisher image_pub_;
  ros::Publisher info_pub_;
  ros::Subscriber projector_sub_;
  sensor_msgs::CameraInfo info_;
  std::map<std::string, ros::WallTime> last_warning_;
  ros::Time last_frame_;
  cv::Mat clean_;         // the noise-free frame of clean_source_
  cv::Mat clean_source_;  // the projector luminance it shows (empty: none)
  cv::Size projector_size_;
  bool failed_ = false;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "demo_camera");
  ros::NodeHandle nh;
  ros::NodeHandle pnh("~");
  std::string type_problems;
  const Options options = readOptions(pnh, type_problems);
  const std::string problems = checkOptions(options, type_problems);
  if (!problems.empty())
  {
    ROS_FATAL("demo_camera: %s", problems.c_str());
    return 1;
  }
  DemoCamera camera(nh, pnh, options);
  ros::spin();
  return camera.failed() ? 1 : 0;
}
