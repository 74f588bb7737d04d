// launch/projector.launch: the mount pose arguments become parent -> body -> optical frame tf with
// the standard body -> optical rotation, and the calibration is published on the CameraInfo topic
// stamped with the optical frame. demo.launch's projector (1.2 m high, 0.15 m ahead of base_link,
// aimed 1 m ahead) is checked geometrically: its beam axis meets the floor at x = 1.15 m.

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <ros/topic.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cmath>
#include <memory>
#include <string>

namespace
{
constexpr double kTolerance = 1e-6;

tf2_ros::Buffer& buffer()
{
  static tf2_ros::Buffer buffer;
  static tf2_ros::TransformListener listener(buffer);
  return buffer;
}

/// parent <- child, waiting up to 15 s for it.
tf2::Transform lookup(const std::string& parent, const std::string& child)
{
  const geometry_msgs::TransformStamped t =
      buffer().lookupTransform(parent, child, ros::Time(0), ros::Duration(15.0));
  tf2::Transform result;
  tf2::fromMsg(t.transform, result);
  return result;
}

/// The standard body (x forward, y left, z up) -> optical (z forward, x right, y down) rotation.
tf2::Quaternion opticalRotation()
{
  return tf2::Quaternion(-0.5, 0.5, -0.5, 0.5);
}

void expectNear(const tf2::Vector3& expected, const tf2::Vector3& actual, const std::string& what)
{
  EXPECT_NEAR(expected.x(), actual.x(), kTolerance) << what;
  EXPECT_NEAR(expected.y(), actual.y(), kTolerance) << what;
  EXPECT_NEAR(expected.z(), actual.z(), kTolerance) << what;
}

void expectSameTransform(const tf2::Transform& expected, const tf2::Transform& actual, const std::string& what)
{
  expectNear(expected.getOrigin(), actual.getOrigin(), what + " translation");
  EXPECT_NEAR(0.0, expected.getRotation().angleShortestPath(actual.getRotation()), kTolerance) << what << " rotation";
}

}  // namespace

TEST(ProjectorLaunch, DemoProjectorMount)
{
  const tf2::Transform base_from_optical = lookup("base_link", "projector_optical_frame");
  tf2::Quaternion mount;
  mount.setRPY(0.0, std::atan2(1.2, 1.0), 0.0);
  const tf2::Transform expected =
      tf2::Transform(mount, tf2::Vector3(0.15, 0.0, 1.2)) * tf2::Transform(opticalRotation());
  expectSameTransform(expected, base_from_optical, "base_link <- projector_optical_frame");

  // The beam's axis (optical +z) meets the floor 1 m ahead of the projector, straight ahead.
  const tf2::Vector3 centre = base_from_optical.getOrigin();
  const tf2::Vector3 axis = base_from_optical.getBasis() * tf2::Vector3(0, 0, 1);
  ASSERT_LT(axis.z(), 0.0);
  const tf2::Vector3 hit = centre + axis * (-centre.z() / axis.z());
  expectNear(tf2::Vector3(1.15, 0.0, 0.0), hit, "beam axis on the floor");
  // Image right (optical +x) is the robot's right (-y); image down (optical +y) is towards the robot.
  expectNear(tf2::Vector3(0, -1, 0), base_from_optical.getBasis() * tf2::Vector3(1, 0, 0), "image right");
  EXPECT_LT((base_from_optical.getBasis() * tf2::Vector3(0, 1, 0)).x(), 0.0) << "image down points backwards";
}

TEST(ProjectorLaunch, DemoProjectorCameraInfo)
{
  const sensor_msgs::CameraInfo::ConstPtr info =
      ros::topic::waitForMessage<sensor_msgs::CameraInfo>("/projector/camera_info", ros::Duration(15.0));
  ASSERT_TRUE(info != nullptr);
  EXPECT_EQ("projector_optical_frame", info->header.frame_id);
  EXPECT_EQ(1280u, info->width);
  EXPECT_EQ(800u, info->height);
  EXPECT_DOUBLE_EQ(1300.0, info->P[0]);
  EXPECT_DOUBLE_EQ(1300.0, info->P[5]);
  EXPECT_DOUBLE_EQ(639.5, info->P[2]);
  EXPECT_DOUBLE_EQ(399.5, info->P[6]);
}

TEST(ProjectorLaunch, EveryMountArgumentInItsPlace)
{
  // roll, pitch and yaw all different: catches a swapped argument order (static_transform_publisher
  // takes yaw pitch roll).
  tf2::Quaternion mount;
  mount.setRPY(0.1, 0.5, -0.3);
  expectSameTransform(tf2::Transform(mount, tf2::Vector3(0.1, -0.2, 0.9)), lookup("robot_top", "tilted_link"),
                      "robot_top <- tilted_link");
  expectSameTransform(tf2::Transform(opticalRotation()), lookup("tilted_link", "tilted_optical"),
                      "tilted_link <- tilted_optical");

  const sensor_msgs::CameraInfo::ConstPtr info =
      ros::topic::waitForMessage<sensor_msgs::CameraInfo>("/tilted/camera_info", ros::Duration(15.0));
  ASSERT_TRUE(info != nullptr);
  EXPECT_EQ("tilted_optical", info->header.frame_id);
  EXPECT_DOUBLE_EQ(1900.0, info->P[0]);
  EXPECT_DOUBLE_EQ(817.0, info->P[6]);
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "projector_launch_test", ros::init_options::AnonymousName);
  ros::NodeHandle nh;  // keeps the node alive for the whole run
  return RUN_ALL_TESTS();
}
