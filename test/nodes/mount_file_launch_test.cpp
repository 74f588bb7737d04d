// projector.launch mount_file:= (issue 12): the tf of a mount file equals the tf of the same mount
// given as x/y/z/roll/pitch/yaw arguments (static_transform_publisher), the file wins over the
// arguments, and both equal the core's opticalPoseOfMount and a rotation built by hand: the
// round trip "against the launch's own tf". Then the solver on floor points made from the launch's
// own tf returns the launch's arguments. A broken mount file stops mount_tf_publisher with status 1
// and a message naming the field.

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <yaml-cpp/yaml.h>

#include <map>
#include <string>
#include <vector>

#include "../support/child_process.h"
#include "mount_oracle.h"
#include "rviz_projector/core/projector_mount.h"

namespace
{
using rviz_projector_test::TestMount;
using rviz_projector_test::TestPoint;

// mount_file_launch.test: the "args" projector's arguments = test/nodes/mount/tilted_mount.yaml.
const TestMount kLaunchMount = {0.1, -0.2, 0.9, 0.1, 0.5, -0.3};
const std::string kPa503w = std::string(CONFIG_DIR) + "/pa503w.yaml";

tf2_ros::Buffer& buffer()
{
  static tf2_ros::Buffer buffer;
  static tf2_ros::TransformListener listener(buffer);
  return buffer;
}

/// parent <- child, waiting up to 20 s for it.
tf2::Transform lookup(const std::string& parent, const std::string& child)
{
  const geometry_msgs::TransformStamped t = buffer().lookupTransform(parent, child, ros::Time(0), ros::Duration(20.0));
  tf2::Transform result;
  tf2::fromMsg(t.transform, result);
  return result;
}

void expectSame(const tf2::Transform& expected, const tf2::Transform& actual, double tolerance, const std::string& what)
{
  for (int i = 0; i < 3; ++i)
  {
    EXPECT_NEAR(expected.getOrigin()[i], actual.getOrigin()[i], tolerance) << what << " translation " << i;
    for (int j = 0; j < 3; ++j)
    {
      EXPECT_NEAR(expected.getBasis()[i][j], actual.getBasis()[i][j], tolerance) << what << " R" << i << j;
    }
  }
}

tf2::Transform fromCore(const rviz_projector::RigidTransform& t)
{
  const auto& r = t.rotation();
  return tf2::Transform(tf2::Matrix3x3(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8]),
                        tf2::Vector3(t.translation().x, t.translation().y, t.translation().z));
}

tf2::Transform fromOracle(const rviz_projector_test::TestPose& p)
{
  const cv::Matx33d& r = p.rotation;
  return tf2::Transform(tf2::Matrix3x3(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)),
                        tf2::Vector3(p.translation[0], p.translation[1], p.translation[2]));
}

rviz_projector_test::RunResult runMountTfPublisher(const std::vector<std::string>& params)
{
  static int run = 0;
  std::vector<std::string> argv = {MOUNT_TF_PUBLISHER_BINARY, "__name:=mount_tf_publisher_run_" + std::to_string(run++)};
  argv.insert(argv.end(), params.begin(), params.end());
  return rviz_projector_test::run(argv, 20.0);
}
}  // namespace

TEST(MountFileLaunch, FileAndArgumentsPublishTheSameTf)
{
  const tf2::Transform from_args = lookup("robot_top", "args_optical");
  const tf2::Transform from_file = lookup("robot_top", "file_optical");
  expectSame(from_args, from_file, 1e-9, "mount_file vs arguments (optical)");
  expectSame(lookup("robot_top", "args_link"), lookup("robot_top", "file_link"), 1e-9,
             "mount_file vs arguments (body)");

  rviz_projector::ProjectorMount mount;
  mount.x = kLaunchMount.x;
  mount.y = kLaunchMount.y;
  mount.z = kLaunchMount.z;
  mount.roll = kLaunchMount.roll;
  mount.pitch = kLaunchMount.pitch;
  mount.yaw = kLaunchMount.yaw;
  expectSame(from_args, fromCore(rviz_projector::opticalPoseOfMount(mount)), 1e-9, "core opticalPoseOfMount");
  expectSame(from_args, fromOracle(rviz_projector_test::opticalPoseByHand(kLaunchMount)), 1e-9, "by hand");

  // And back: the core's inverse gives the launch's arguments from the launch's tf.
  const tf2::Quaternion q = from_args.getRotation();
  const rviz_projector::ProjectorMount back = rviz_projector::mountOfOpticalPose(rviz_projector::RigidTransform::fromQuaternion(
      q.x(), q.y(), q.z(), q.w(), {from_args.getOrigin().x(), from_args.getOrigin().y(), from_args.getOrigin().z()}));
  EXPECT_NEAR(kLaunchMount.x, back.x, 1e-9);
  EXPECT_NEAR(kLaunchMount.y, back.y, 1e-9);
  EXPECT_NEAR(kLaunchMount.z, back.z, 1e-9);
  EXPECT_NEAR(kLaunchMount.roll, back.roll, 1e-9);
  EXPECT_NEAR(kLaunchMount.pitch, back.pitch, 1e-9);
  EXPECT_NEAR(kLaunchMount.yaw, back.yaw, 1e-9);
}

TEST(MountFileLaunch, SolvedFromTheLaunchsOwnTfGivesTheLaunchArguments)
{
  const tf2::Transform optical = lookup("robot_top", "args_optical");
  image_geometry::PinholeCameraModel lens;
  ASSERT_TRUE(rviz_projector_test::lensFromFile(kPa503w, lens));
  rviz_projector_test::TestPose pose;
  for (int i = 0; i < 3; ++i)
  {
    pose.translation[i] = optical.getOrigin()[i];
    for (int j = 0; j < 3; ++j)
    {
      pose.rotation(i, j) = optical.getBasis()[i][j];
    }
  }
  std::vector<TestPoint> points;
  int id = 1;
  for (const double v : {80.0, 400.0, 720.0})
  {
    for (const double u : {128.0, 640.0, 1152.0})
    {
      TestPoint p{id++, u, v, {}};
      ASSERT_TRUE(rviz_projector_test::pixelOnPlane(lens, pose, u, v, 0.0, p.world));
      points.push_back(p);
    }
  }
  const std::string dir = rviz_projector_test::makeTempDir();
  rviz_projector_test::writeFile(dir + "/points.yaml", rviz_projector_test::pointsYaml("robot_top", points));
  const auto result = rviz_projector_test::run({CALIBRATE_PROJECTOR_BINARY, "--camera-info", kPa503w, "--points",
                                                dir + "/points.yaml", "--output", dir + "/mount.yaml"});
  ASSERT_EQ(0, result.status) << result.out << result.err;
  const YAML::Node mount = YAML::LoadFile(dir + "/mount.yaml");
  EXPECT_EQ("robot_top", mount["parent_frame"].as<std::string>());
  EXPECT_NEAR(kLaunchMount.x, mount["x"].as<double>(), 1e-6);
  EXPECT_NEAR(kLaunchMount.y, mount["y"].as<double>(), 1e-6);
  EXPECT_NEAR(kLaunchMount.z, mount["z"].as<double>(), 1e-6);
  EXPECT_NEAR(kLaunchMount.roll, mount["roll"].as<double>(), 1e-6);
  EXPECT_NEAR(kLaunchMount.pitch, mount["pitch"].as<double>(), 1e-6);
  EXPECT_NEAR(kLaunchMount.yaw, mount["yaw"].as<double>(), 1e-6);
}

TEST(MountFileLaunch, RelativePathIsTakenFromTheBaseDirectory)
{
  rviz_projector_test::ChildProcess node({MOUNT_TF_PUBLISHER_BINARY, "__name:=mount_tf_publisher_relative",
                                          "_mount_file:=tilted_mount.yaml",
                                          std::string("_base_directory:=") + MOUNT_TEST_DIR, "_frame:=relative_link"});
  ASSERT_TRUE(node.ok());
  expectSame(lookup("robot_top", "args_link"), lookup("robot_top", "relative_link"), 1e-9, "relative mount_file");
}

struct BrokenMount
{
  std::string file;
  std::string expected;
};

TEST(MountFileLaunch, BrokenMountFileStopsTheNodeNamingTheField)
{
  const std::string dir = MOUNT_TEST_DIR;
  const std::vector<BrokenMount> cases = {
      {dir + "/no_such_mount.yaml", "no_such_mount.yaml: cannot be read"},
      {dir + "/bad_syntax.yaml", "bad_syntax.yaml: not valid YAML: line"},
      {dir + "/no_pitch.yaml", "no_pitch.yaml: missing field 'pitch'"},
      {dir + "/nan_yaw.yaml", "nan_yaw.yaml: field 'yaw' is not finite"},
      {dir + "/text_z.yaml", "text_z.yaml: field 'z' is not a number (got 'high')"},
      {dir + "/no_parent_frame.yaml", "no_parent_frame.yaml: missing field 'parent_frame'"},
      {"", "parameter"},
  };
  for (const BrokenMount& broken : cases)
  {
    const auto result = runMountTfPublisher({"_mount_file:=" + broken.file});
    const std::string output = result.out + result.err;
    EXPECT_EQ(1, result.status) << broken.file << "\n" << output;
    EXPECT_NE(std::string::npos, output.find("FATAL")) << output;
    EXPECT_NE(std::string::npos, output.find(broken.expected)) << "missing '" << broken.expected << "' in\n"
                                                               << output;
  }
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "mount_file_launch_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
