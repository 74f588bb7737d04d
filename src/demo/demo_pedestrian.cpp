// demo_pedestrian: a simulated person who keeps crossing the demo robot's path, and the robot's
// laser scanner seeing them, for the ProjectionMask display (no light on people) in the demo.
//
// Every `pause` + crossing seconds the person starts a crossing `ahead` metres in front of the robot
// (in the map frame, fixed for that crossing) and walks across the robot's heading from one side to
// the other at `speed`, then stands aside. A scanner mounted on the robot (static tf base_link ->
// base_laser, `laser_x` ahead, `laser_z` up) sees the person as a circle of `radius` metres
// (simulateScan, rviz_projector core) and publishes the scan at `rate` Hz, stamped with the tf time
// it was simulated for.
//
// Topics:   /demo/scan        sensor_msgs/LaserScan, frame base_laser
//           /demo/pedestrian  visualization_msgs/MarkerArray (a body and a head, map frame) for the main view
// tf:       static base_link -> base_laser
#include <cmath>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/utils.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>

#include "rviz_projector/core/scan_simulation.h"
#include "ros_time_scheduler.h"

namespace
{
using rviz_projector::Circle;
using rviz_projector::ScanGeometry;
using rviz_projector::Vec2;

constexpr const char* kMapFrame = "map";
constexpr const char* kBaseFrame = "base_link";
constexpr const char* kLaserFrame = "base_laser";

class DemoPedestrian
{
public:
  DemoPedestrian() : pnh_("~"), listener_(buffer_)
  {
    pnh_.param("ahead", ahead_, 2.2);
    pnh_.param("half_width", half_width_, 1.0);
    pnh_.param("speed", speed_, 0.5);
    pnh_.param("pause", pause_, 1.5);
    pnh_.param("radius", radius_, 0.22);
    pnh_.param("laser_x", laser_x_, 0.2);
    pnh_.param("laser_z", laser_z_, 0.3);
    double rate = 10.0;
    pnh_.param("rate", rate, 10.0);
    // Each unusable value falls back to its own default (the others are kept), with a warning.
    const auto positive = [](const char* name, double& value, double fallback, bool zero_ok) {
      if (!(zero_ok ? value >= 0.0 : value > 0.0) || !std::isfinite(value))
      {
        ROS_WARN("demo_pedestrian: ~%s = %g must be %s: %g used", name, value, zero_ok ? ">= 0" : "> 0", fallback);
        value = fallback;
      }
    };
    positive("speed", speed_, 0.5, false);
    positive("half_width", half_width_, 1.0, false);
    positive("rate", rate, 10.0, false);
    positive("radius", radius_, 0.22, false);
    positive("pause", pause_, 1.5, true);
    scan_pub_ = nh_.advertise<sensor_msgs::LaserScan>("/demo/scan", 5);
    marker_pub_ = nh_.advertise<visualization_msgs::MarkerArray>("/demo/pedestrian", 5);
    geometry_msgs::TransformStamped mount;
    mount.header.stamp = ros::Time::now();
    mount.header.frame_id = kBaseFrame;
    mount.child_frame_id = kLaserFrame;
    mount.transform.translation.x = laser_x_;
    mount.transform.translation.z = laser_z_;
    mount.transform.rotation.w = 1.0;
    static_broadcaster_.sendTransform(mount);
    scheduler_.add(1.0 / rate, [this] { step(); });
    scheduler_.start(nh_);
  }

private:
  void step()
  {
    geometry_msgs::TransformStamped laser;
    try
    {
      laser = buffer_.lookupTransform(kMapFrame, kLaserFrame, ros::Time(0));
    }
    catch (const tf2::TransformException& e)
    {
      ROS_WARN_THROTTLE(5.0, "demo_pedestrian: waiting for tf %s -> %s: %s", kMapFrame, kLaserFrame, e.what());
      return;
    }
    const Vec2 origin{laser.transform.translation.x, laser.transform.translation.y};
    const double yaw = tf2::getYaw(laser.transform.rotation);
    const double now = laser.header.stamp.toSec();
    const double crossing = 2.0 * half_width_ / speed_;
    if (!started_ || now - start_ > crossing + pause_ || now < start_)
    {
      // A new crossing ahead of the robot, from the side the last one ended on.
      started_ = true;
      start_ = now;
      side_ = -side_;
      const Vec2 forward{std::cos(yaw), std::sin(yaw)};
      const Vec2 left{-forward.y, forward.x};
      const Vec2 centre = origin + forward * ahead_;
      from_ = centre + left * (side_ * half_width_);
      to_ = centre - left * (side_ * half_width_);
    }
    const double walked = std::min(1.0, std::max(0.0, (now - start_) / crossing));
    const Vec2 person = from_ + (to_ - from_) * walked;

    rviz_projector::simulateScan(geometry_, origin, yaw, {Circle{person, radius_}}, ranges_);
    sensor_msgs::LaserScan scan;
    scan.header.stamp = laser.header.stamp.isZero() ? ros::Time::now() : laser.header.stamp;
    scan.header.frame_id = kLaserFrame;
    scan.angle_min = static_cast<float>(geometry_.angle_min);
    scan.angle_increment = static_cast<float>(geometry_.angle_increment);
    scan.angle_max = static_cast<float>(geometry_.angle_min + (geometry_.beams - 1) * geometry_.angle_increment);
    scan.range_min = static_cast<float>(geometry_.range_min);
    scan.range_max = static_cast<float>(geometry_.range_max);
    scan.ranges = ranges_;
    scan_pub_.publish(scan);
    publishMarkers(person, scan.header.stamp);
  }

  void publishMarkers(const Vec2& person, const ros::Time& stamp)
  {
    visualization_msgs::MarkerArray markers;
    visualization_msgs::Marker body;
    body.header.frame_id = kMapFrame;
    body.header.stamp = stamp;
    body.ns = "pedestrian";
    body.id = 0;
    body.type = visualization_msgs::Marker::CYLINDER;
    body.pose.position.x = person.x;
    body.pose.position.y = person.y;
    body.pose.position.z = 0.75;
    body.pose.orientation.w = 1.0;
    body.scale.x = body.scale.y = 2.0 * radius_;
    body.scale.z = 1.5;
    body.color.r = 0.2f;
    body.color.g = 0.5f;
    body.color.b = 1.0f;
    body.color.a = 0.8f;
    body.lifetime = ros::Duration(1.0);
    visualization_msgs::Marker head = body;
    head.id = 1;
    head.type = visualization_msgs::Marker::SPHERE;
    head.pose.position.z = 1.62;
    head.scale.x = head.scale.y = head.scale.z = 0.24;
    markers.markers = {body, head};
    marker_pub_.publish(markers);
  }

  ros::NodeHandle nh_;
  ros::NodeHandle pnh_;
  tf2_ros::Buffer buffer_;
  tf2_ros::TransformListener listener_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  ros::Publisher scan_pub_;
  ros::Publisher marker_pub_;
  rviz_projector_demo::RosTimeScheduler scheduler_{"demo_pedestrian"};  // the scan, on ROS time
  ScanGeometry geometry_;
  std::vector<float> ranges_;
  double ahead_ = 2.2, half_width_ = 1.0, speed_ = 0.5, pause_ = 1.5, radius_ = 0.22, laser_x_ = 0.2, laser_z_ = 0.3;
  bool started_ = false;
  double start_ = 0.0;
  double side_ = 1.0;
  Vec2 from_, to_;
};
}  // namespace

int main(int argc, char** argv)
{
  ros::init(argc, argv, "demo_pedestrian");
  DemoPedestrian pedestrian;
  ros::spin();
  return 0;
}
