// rviz_projector_slip_probe: the motion slip benchmark's synthetic robot and probe, in one process
// (scripts/bench --slip; issue 14, "Measured, in the benchmark").
//
// The robot: base_link follows an analytic trajectory (bench/e2e/slip_geometry.h: still, turn in
// place at 0.5 rad/s, straight at 1 m/s, S-curve at 0.7 m/s with +-0.6 rad/s) in the fixed frame
// map; tf map -> base_link at 50 Hz (--tf-rate) stamped with ros::Time::now() and the pose of that
// instant, and the same motion as nav_msgs/Odometry on /slip/odom (twist in base_link);
// the demo's projector mount as a static base_link -> projector_optical_frame and its CameraInfo
// (latched, /projector/camera_info). World-locked thin white stripes on the floor (a latched
// visualization_msgs/Marker TRIANGLE_LIST in map, one pattern per motion).
//
// The probe: reads ONE row of the projector's output window (image row --row, ~1.6 m ahead of the
// projector) about every millisecond with MIT-SHM, finds the lit runs (stripes crossing the row),
// takes each run's centre (sub-pixel), and computes from the analytic trajectory at the sample time
// (plus --truth-lags ms: a projector's simulated input lag) the floor point that pixel's ray lights
// and its signed distance across the nearest true stripe. Positive: the drawn stripe lies displaced
// along the robot's motion at that point (drawn from an older pose: it lags behind the motion).
//
// Output (--out, appended, tab separated):
//   slip  SETTING  LAG_MS  MOTION  T_MS  APPEAR  SLIP_MM  SPEED   one per crossing per sample
//   meta  SETTING  LAG_MS  MOTION  KEY   VALUE                 samples, frames, rates, misses
// --tf-lead-ms D checks the bench itself: tf then carries, stamped now, the pose of now + D (an
// ideal predictor outside the pipeline, for a constant delay D): the slip must drop to what the
// hold between frames alone makes.
//
// APPEAR is 1 when the row differed from the previous sample (a new frame showed up), else 0;
// SPEED (m/s) is how fast the floor there moves across the stripe (slip / speed = the delay).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/Marker.h>

#include "slip_geometry.h"
#include "slip_x11.h"

namespace
{
using Clock = std::chrono::steady_clock;
using slip::Motion;

[[noreturn]] void fail(const std::string& what)
{
  std::fprintf(stderr, "slip_probe: %s\n", what.c_str());
  std::exit(2);
}

void note(const std::string& what)
{
  std::fprintf(stderr, "[slip_probe] %s\n", what.c_str());
}

std::vector<std::string> split(const std::string& s, char sep)
{
  std::vector<std::string> parts;
  std::stringstream in(s);
  std::string part;
  while (std::getline(in, part, sep))
  {
    if (!part.empty()) parts.push_back(part);
  }
  return parts;
}

struct Options
{
  std::string window = "Projector: Projector";
  std::string setting = "off";
  std::vector<double> truth_lags_ms{0.0};
  std::vector<Motion> motions{Motion::Still, Motion::Turn, Motion::Straight, Motion::SCurve, Motion::SCurveSteps};
  double warmup = 2.0;       // s, per motion
  double trial = 9.0;        // s, per motion
  double still_trial = 3.0;  // s
  int row = 100;             // image row sampled
  double rate = 1000.0;      // samples/s
  int threshold = 64;        // a pixel is lit when a colour channel reaches this
  double tf_lead_ms = 0.0;   // check of the bench itself: tf carries the pose this much ahead
  double tf_rate = 50.0;     // Hz of map -> base_link (and of the odometry)
  double info_rate = 0.0;    // Hz: the same CameraInfo again, a new stamp each time, as camera drivers
                             // and `rostopic pub -r` do (0: once, latched)
  std::string out;
};

Options parseOptions(int argc, char** argv)
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) fail("missing value for " + a);
      return argv[++i];
    };
    if (a == "--window") o.window = value();
    else if (a == "--setting") o.setting = value();
    else if (a == "--truth-lags")
    {
      o.truth_lags_ms.clear();
      for (const auto& s : split(value(), ',')) o.truth_lags_ms.push_back(std::stod(s));
    }
    else if (a == "--motions")
    {
      o.motions.clear();
      for (const auto& s : split(value(), ','))
      {
        Motion m;
        if (!slip::parseMotion(s, m)) fail("unknown motion " + s + " (still, turn, straight, scurve, scurve-steps)");
        o.motions.push_back(m);
      }
    }
    else if (a == "--warmup") o.warmup = std::stod(value());
    else if (a == "--trial") o.trial = std::stod(value());
    else if (a == "--still-trial") o.still_trial = std::stod(value());
    else if (a == "--row") o.row = std::stoi(value());
    else if (a == "--rate") o.rate = std::stod(value());
    else if (a == "--threshold") o.threshold = std::stoi(value());
    else if (a == "--tf-lead-ms") o.tf_lead_ms = std::stod(value());
    else if (a == "--tf-rate") o.tf_rate = std::stod(value());
    else if (a == "--info-rate") o.info_rate = std::stod(value());
    else if (a == "--out") o.out = value();
    else if (a.rfind("__", 0) == 0 || a.find(":=") != std::string::npos) continue;  // ROS remaps
    else fail("unknown option " + a);
  }
  if (o.truth_lags_ms.empty() || o.motions.empty()) fail("--truth-lags and --motions need values");
  if (o.rate <= 0.0 || o.trial <= 0.0 || o.tf_rate <= 0.0) fail("--rate, --trial and --tf-rate must be positive");
  return o;
}

/// The robot: which motion, since when (guarded: the tf thread reads it).
class Robot
{
public:
  void start(Motion m, const ros::Time& t0)
  {
    std::lock_guard<std::mutex> lock(mutex_);
    motion_ = m;
    t0_ = t0;
  }
  slip::RobotState at(const ros::Time& t) const
  {
    std::lock_guard<std::mutex> lock(mutex_);
    return slip::robotState(motion_, (t - t0_).toSec());
  }

private:
  mutable std::mutex mutex_;
  Motion motion_ = Motion::Still;
  ros::Time t0_;
};

/// The mount as tf publishes it: Ry(pitch) then the body -> optical quaternion.
tf2::Quaternion mountRotation()
{
  tf2::Quaternion pitch;
  pitch.setRPY(0.0, std::atan2(1.2, 1.0), 0.0);
  return pitch * tf2::Quaternion(-0.5, 0.5, -0.5, 0.5);
}

sensor_msgs::CameraInfo cameraInfo(const slip::Projector& p)
{
  sensor_msgs::CameraInfo info;
  info.header.frame_id = "projector_optical_frame";
  info.header.stamp = ros::Time::now();
  info.width = static_cast<unsigned>(p.width);
  info.height = static_cast<unsigned>(p.height);
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  info.K = {p.fx, 0.0, p.cx, 0.0, p.fy, p.cy, 0.0, 0.0, 1.0};
  info.R = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  info.P = {p.fx, 0.0, p.cx, 0.0, 0.0, p.fy, p.cy, 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

visualization_msgs::Marker stripeMarker(const slip::StripePattern& pattern)
{
  visualization_msgs::Marker m;
  m.header.frame_id = "map";
  m.header.stamp = ros::Time(0);
  m.ns = "slip_stripes";
  m.id = 0;
  m.type = visualization_msgs::Marker::TRIANGLE_LIST;
  m.action = visualization_msgs::Marker::ADD;
  m.pose.orientation.w = 1.0;
  m.scale.x = m.scale.y = m.scale.z = 1.0;
  m.color.r = m.color.g = m.color.b = m.color.a = 1.0f;
  const double half = 0.5 * pattern.width();
  for (const slip::Stripe& s : pattern.stripes())
  {
    const double dx = s.b.x - s.a.x, dy = s.b.y - s.a.y, len = std::hypot(dx, dy);
    const double nx = -dy / len * half, ny = dx / len * half;
    geometry_msgs::Point c[4];
    c[0].x = s.a.x + nx, c[0].y = s.a.y + ny;
    c[1].x = s.a.x - nx, c[1].y = s.a.y - ny;
    c[2].x = s.b.x - nx, c[2].y = s.b.y - ny;
    c[3].x = s.b.x + nx, c[3].y = s.b.y + ny;
    // On the floor itself (z = 0, nothing else is drawn there): 1 mm up, the light of a stripe would
    // land ~1.3 mm farther along the beam, which the still check shows.
    for (auto& p : c) p.z = 0.0;
    for (int i : {0, 1, 2, 0, 2, 3}) m.points.push_back(c[i]);
  }
  return m;
}

/// Centres (window column, sub-pixel: the middle of the lit run) of the runs fully inside the row.
std::vector<double> litRuns(const std::vector<std::uint32_t>& row, int threshold)
{
  std::vector<double> centres;
  auto lit = [&](std::uint32_t p) {
    return static_cast<int>((p >> 16) & 0xFF) >= threshold || static_cast<int>((p >> 8) & 0xFF) >= threshold ||
           static_cast<int>(p & 0xFF) >= threshold;
  };
  const int n = static_cast<int>(row.size());
  for (int i = 0; i < n;)
  {
    if (!lit(row[static_cast<std::size_t>(i)]))
    {
      ++i;
      continue;
    }
    int j = i;
    while (j + 1 < n && lit(row[static_cast<std::size_t>(j + 1)])) ++j;
    if (i > 0 && j < n - 1) centres.push_back(0.5 * (i + j));
    i = j + 1;
  }
  return centres;
}

class SlipBench
{
public:
  explicit SlipBench(const Options& o) : o_(o), projector_(slip::demoProjector())
  {
    if (!o_.out.empty())
    {
      out_.open(o_.out, std::ios::app);
      if (!out_) fail("cannot write " + o_.out);
    }
    checkMount();
    info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>("/projector/camera_info", 1, true);
    marker_pub_ = nh_.advertise<visualization_msgs::Marker>("/slip/stripes", 1, true);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/slip/odom", 10);
  }

  void run()
  {
    publishStatic();
    robot_.start(Motion::Still, ros::Time::now());
    marker_pub_.publish(stripeMarker(slip::StripePattern::forMotion(Motion::Still)));
    tf_thread_ = std::thread([this] { publishTf(); });
    findImageRow();
    waitForStripes();
    for (Motion m : o_.motions)
    {
      measure(m);
    }
    stop_ = true;
    tf_thread_.join();
  }

private:
  /// The geometry's mount matrix must be the rotation tf publishes (or the truth is of another robot).
  void checkMount() const
  {
    const tf2::Matrix3x3 r(mountRotation());
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (std::abs(r[i][j] - projector_.mount_r[static_cast<std::size_t>(3 * i + j)]) > 1e-9)
          fail("the mount published on tf differs from the geometry's");
  }

  void publishStatic()
  {
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = "base_link";
    t.child_frame_id = "projector_optical_frame";
    t.transform.translation.x = projector_.mount_t[0];
    t.transform.translation.y = projector_.mount_t[1];
    t.transform.translation.z = projector_.mount_t[2];
    const tf2::Quaternion q = mountRotation();
    t.transform.rotation.x = q.x();
    t.transform.rotation.y = q.y();
    t.transform.rotation.z = q.z();
    t.transform.rotation.w = q.w();
    static_broadcaster_.sendTransform(t);
    info_pub_.publish(cameraInfo(projector_));
  }

  void publishTf()
  {
    tf2_ros::TransformBroadcaster broadcaster;
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / o_.tf_rate));
    auto next = Clock::now();
    double next_info = 0.0;
    sensor_msgs::CameraInfo info = cameraInfo(projector_);
    while (!stop_ && ros::ok())
    {
      next += period;
      std::this_thread::sleep_until(next);
      const ros::Time now = ros::Time::now();
      if (o_.info_rate > 0.0 && now.toSec() >= next_info)
      {
        // The same lens with every "camera frame" (at most the tf rate), a new stamp each time.
        info.header.stamp = now;
        info_pub_.publish(info);
        next_info = now.toSec() + 1.0 / o_.info_rate;
      }
      const slip::RobotState s = robot_.at(now + ros::Duration(o_.tf_lead_ms / 1000.0));
      geometry_msgs::TransformStamped t;
      t.header.stamp = now;
      t.header.frame_id = "map";
      t.child_frame_id = "base_link";
      t.transform.translation.x = s.x;
      t.transform.translation.y = s.y;
      tf2::Quaternion q;
      q.setRPY(0.0, 0.0, s.yaw);
      t.transform.rotation.x = q.x();
      t.transform.rotation.y = q.y();
      t.transform.rotation.z = q.z();
      t.transform.rotation.w = q.w();
      broadcaster.sendTransform(t);
      // The same motion as nav_msgs/Odometry (twist in base_link), for the Odometry topic property.
      nav_msgs::Odometry odom;
      odom.header = t.header;
      odom.child_frame_id = "base_link";
      odom.pose.pose.position.x = s.x;
      odom.pose.pose.position.y = s.y;
      odom.pose.pose.orientation = t.transform.rotation;
      odom.twist.twist.linear.x = std::cos(s.yaw) * s.vx + std::sin(s.yaw) * s.vy;
      odom.twist.twist.linear.y = -std::sin(s.yaw) * s.vx + std::cos(s.yaw) * s.vy;
      odom.twist.twist.angular.z = s.yaw_rate;
      odom_pub_.publish(odom);
    }
  }

  void findImageRow()
  {
    note("looking for a window titled '" + o_.window + "'");
    const auto deadline = Clock::now() + std::chrono::seconds(90);
    Window w = 0;
    while ((w = screen_.findWindow(o_.window)) == 0)
    {
      if (Clock::now() > deadline) fail("no viewable window titled '" + o_.window + "'");
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
    }
    // Full screen takes a moment after mapping: wait until the size stops changing.
    slip::ScreenRect win = screen_.windowRect(w);
    for (int stable = 0; stable < 5 && Clock::now() < deadline;)
    {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      const slip::ScreenRect now = screen_.windowRect(w);
      stable = now.width == win.width && now.height == win.height && now.x == win.x && now.y == win.y ? stable + 1 : 0;
      win = now;
    }
    const slip::ScreenRect img = slip::imageRectInWindow(projector_.width, projector_.height, win.width, win.height);
    if (img.width <= 0 || img.height <= 0) fail("empty output window");
    // Image coordinates (pixel centres at integers) <-> window pixels: u = (x + 0.5) * iw / w - 0.5.
    scale_x_ = static_cast<double>(projector_.width) / img.width;
    const double scale_y = static_cast<double>(projector_.height) / img.height;
    const int window_row = static_cast<int>(std::lround((o_.row + 0.5) / scale_y - 0.5));
    v_ = (window_row + 0.5) * scale_y - 0.5;
    origin_x_ = win.x + img.x;
    char text[240];
    std::snprintf(text, sizeof text,
                  "window %dx%d+%d+%d, image %dx%d at +%d+%d in it; sampling screen row %d (image row %.2f)",
                  win.width, win.height, win.x, win.y, img.width, img.height, img.x, img.y, win.y + img.y + window_row,
                  v_);
    note(text);
    emitMeta("setup", "window_width", win.width);
    emitMeta("setup", "window_height", win.height);
    emitMeta("setup", "image_width_on_screen", img.width);
    emitMeta("setup", "image_row", v_);
    screen_.watchRow(origin_x_, win.y + img.y + window_row, img.width);
  }

  void waitForStripes()
  {
    note("waiting for the stripes to show up in the sampled row");
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (litRuns(screen_.grabRow(), o_.threshold).empty())
    {
      if (Clock::now() > deadline) fail("no stripe crossed the sampled row within 60 s (is the projector drawing?)");
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }

  struct Crossing
  {
    float t_ms;
    bool appear;
    int lag_index;
    float slip_mm;
    float speed;
  };

  void measure(Motion m)
  {
    const std::string name = slip::motionName(m);
    const slip::StripePattern pattern = slip::StripePattern::forMotion(m);
    marker_pub_.publish(stripeMarker(pattern));
    const ros::Time t0 = ros::Time::now();
    robot_.start(m, t0);
    note(name + ": warming up");
    std::this_thread::sleep_for(std::chrono::duration<double>(m == Motion::Still ? 1.5 : o_.warmup));

    const double length = m == Motion::Still ? o_.still_trial : o_.trial;
    const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / o_.rate));
    std::vector<Crossing> crossings;
    crossings.reserve(static_cast<std::size_t>(length * o_.rate * 8));
    std::vector<std::uint32_t> previous = screen_.grabRow();
    long samples = 0, appearances = 0, empty = 0, late = 0;
    std::vector<long> ambiguous(o_.truth_lags_ms.size(), 0);
    double max_gap_ms = 0.0;
    const ros::Time start = ros::Time::now();
    ros::Time last = start;
    auto next = Clock::now();
    const auto end = next + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(length));
    while (next < end && ros::ok())
    {
      next += period;
      if (next < Clock::now() - period)
      {
        next = Clock::now();  // fell behind (the machine is busy): no burst to catch up
        ++late;
      }
      std::this_thread::sleep_until(next);
      const ros::Time before = ros::Time::now();
      const std::vector<std::uint32_t>& row = screen_.grabRow();
      const ros::Time after = ros::Time::now();
      const ros::Time t = before + ros::Duration((after - before).toSec() / 2.0);
      max_gap_ms = std::max(max_gap_ms, 1000.0 * (t - last).toSec());
      last = t;
      ++samples;
      const bool appear = row != previous;
      appearances += appear ? 1 : 0;
      previous = row;
      const std::vector<double> runs = litRuns(row, o_.threshold);
      empty += runs.empty() ? 1 : 0;
      for (std::size_t k = 0; k < o_.truth_lags_ms.size(); ++k)
      {
        const slip::RobotState state = robot_.at(t + ros::Duration(o_.truth_lags_ms[k] / 1000.0));
        for (double x : runs)
        {
          slip::Vec2 p;
          if (!slip::floorPoint(projector_, state, (x + 0.5) * scale_x_ - 0.5, v_, p)) continue;
          bool unsure = false;
          double speed = 0.0;
          const double s = slip::slipAt(pattern, state, p, unsure, &speed);
          if (unsure)
          {
            ++ambiguous[k];
            continue;
          }
          crossings.push_back(Crossing{static_cast<float>(1000.0 * (t - start).toSec()), appear, static_cast<int>(k),
                                       static_cast<float>(1000.0 * s), static_cast<float>(speed)});
        }
      }
    }
    const double seconds = (last - start).toSec();
    for (std::size_t k = 0; k < o_.truth_lags_ms.size(); ++k)
    {
      const double lag = o_.truth_lags_ms[k];
      emitMeta(name, "samples", static_cast<double>(samples), lag);
      emitMeta(name, "samples_per_s", samples / seconds, lag);
      emitMeta(name, "frames_per_s", appearances / seconds, lag);
      emitMeta(name, "samples_without_stripes", static_cast<double>(empty), lag);
      emitMeta(name, "crossings_ambiguous", static_cast<double>(ambiguous[k]), lag);
      emitMeta(name, "late_samples", static_cast<double>(late), lag);
      emitMeta(name, "max_gap_ms", max_gap_ms, lag);
    }
    std::string lines;
    char line[160];
    for (const Crossing& c : crossings)
    {
      std::snprintf(line, sizeof line, "slip\t%s\t%g\t%s\t%.1f\t%d\t%.3f\t%.3f\n", o_.setting.c_str(),
                    o_.truth_lags_ms[static_cast<std::size_t>(c.lag_index)], name.c_str(), c.t_ms, c.appear ? 1 : 0,
                    c.slip_mm, c.speed);
      lines += line;
    }
    write(lines);
    char text[200];
    std::snprintf(text, sizeof text, "%s: %ld samples (%.0f/s), %.1f frames/s, %zu crossings", name.c_str(), samples,
                  samples / seconds, appearances / seconds, crossings.size());
    note(text);
  }

  void emitMeta(const std::string& motion, const std::string& key, double value, double lag = 0.0)
  {
    char line[256];
    std::snprintf(line, sizeof line, "meta\t%s\t%g\t%s\t%s\t%.6g\n", o_.setting.c_str(), lag, motion.c_str(),
                  key.c_str(), value);
    write(line);
  }

  void write(const std::string& text)
  {
    if (out_.is_open())
      out_ << text << std::flush;
    else
      std::fputs(text.c_str(), stdout);
  }

  Options o_;
  slip::Projector projector_;
  slip::XScreen screen_;
  Robot robot_;
  std::ofstream out_;
  ros::NodeHandle nh_;
  ros::Publisher info_pub_, marker_pub_, odom_pub_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  std::thread tf_thread_;
  std::atomic<bool> stop_{false};
  double scale_x_ = 1.0, v_ = 0.0;
  int origin_x_ = 0;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "rviz_projector_slip_probe", ros::init_options::AnonymousName);
  const Options options = parseOptions(argc, argv);
  try
  {
    SlipBench bench(options);
    bench.run();
  }
  catch (const std::exception& e)
  {
    fail(e.what());
  }
  return 0;
}
