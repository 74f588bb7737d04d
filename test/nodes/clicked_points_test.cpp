// calibrate_projector --clicked-points (issue 12): the test plays the user in rviz. For every
// prompt "Crosshair N of 9 at pixel (u U, v V)" it publishes, on /clicked_point in the map frame,
// where that pixel lands on the floor for a known mount (oracle: image_geometry + a hand-built
// rotation, test/nodes/mount_oracle.h), taken from base_link into map by hand with
// clicked_points.test's map -> base_link transform. The tool must take each point back into
// base_link with tf, write points.yaml and solve the known mount. The first click is in a frame
// tf does not know: the tool says so and asks again.

#include <geometry_msgs/PointStamped.h>
#include <gtest/gtest.h>
#include <ros/ros.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../support/child_process.h"
#include "mount_oracle.h"

namespace
{
using rviz_projector_test::TestMount;

const std::string kPa503w = std::string(CONFIG_DIR) + "/pa503w.yaml";
const TestMount kMount = {0.15, 0.05, 1.1, -0.03, 0.9, 0.08};
// clicked_points.test: map -> base_link is x 2.0, y 1.0, yaw 0.5.
const double kMapX = 2.0;
const double kMapY = 1.0;
const double kMapYaw = 0.5;

bool waitForSubscriber(const ros::Publisher& publisher, double timeout_s)
{
  const auto start = std::chrono::steady_clock::now();
  ros::WallRate poll(100.0);
  while (publisher.getNumSubscribers() == 0)
  {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_s)
    {
      return false;
    }
    poll.sleep();
  }
  return true;
}

/// The next stdout line containing `text` (other lines skipped); false on timeout or EOF.
bool waitForLine(rviz_projector_test::ChildProcess& child, const std::string& text, std::string& line,
                 double timeout_s = 20.0)
{
  while (child.readLine(line, timeout_s))
  {
    if (line.find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

geometry_msgs::PointStamped click(const std::string& frame, const cv::Vec3d& base_point)
{
  geometry_msgs::PointStamped msg;
  msg.header.frame_id = frame;
  msg.header.stamp = ros::Time::now();
  const double c = std::cos(kMapYaw), s = std::sin(kMapYaw);
  msg.point.x = kMapX + c * base_point[0] - s * base_point[1];
  msg.point.y = kMapY + s * base_point[0] + c * base_point[1];
  msg.point.z = base_point[2];
  return msg;
}
}  // namespace

TEST(CalibrateProjectorClickedPoints, AsksForEachCrosshairTransformsWritesAndSolves)
{
  ros::NodeHandle nh;
  ros::Publisher publisher = nh.advertise<geometry_msgs::PointStamped>("/clicked_point", 10);
  image_geometry::PinholeCameraModel lens;
  ASSERT_TRUE(rviz_projector_test::lensFromFile(kPa503w, lens));
  const rviz_projector_test::TestPose pose = rviz_projector_test::opticalPoseByHand(kMount);

  const std::string dir = rviz_projector_test::makeTempDir();
  rviz_projector_test::ChildProcess tool({CALIBRATE_PROJECTOR_BINARY, "--clicked-points", "--camera-info", kPa503w,
                                          "--points-out", dir + "/points.yaml", "--output", dir + "/mount.yaml"});
  ASSERT_TRUE(tool.ok());

  std::vector<cv::Vec3d> expected(10);
  std::vector<std::pair<double, double>> pixels(10);
  for (int n = 1; n <= 9; ++n)
  {
    std::string line;
    ASSERT_TRUE(waitForLine(tool, "Crosshair ", line)) << "no prompt for crosshair " << n << ":\n" << tool.output();
    int id = 0, count = 0;
    double u = 0.0, v = 0.0;
    ASSERT_EQ(4, std::sscanf(line.c_str(), "Crosshair %d of %d at pixel (u %lf, v %lf)", &id, &count, &u, &v)) << line;
    EXPECT_EQ(n, id);
    EXPECT_EQ(9, count);
    pixels[id] = {u, v};
    ASSERT_TRUE(rviz_projector_test::pixelOnPlane(lens, pose, u, v, 0.0, expected[id])) << line;
    if (n == 1)
    {
      ASSERT_TRUE(waitForSubscriber(publisher, 20.0)) << "calibrate_projector does not subscribe /clicked_point";
      publisher.publish(click("nowhere", expected[id]));
      ASSERT_TRUE(waitForLine(tool, "cannot transform", line)) << tool.output();
      EXPECT_NE(std::string::npos, line.find("'nowhere'")) << line;
    }
    publisher.publish(click("map", expected[id]));
  }
  const int status = tool.wait(60.0);
  ASSERT_EQ(0, status) << tool.output() << tool.errors();

  const YAML::Node points = YAML::LoadFile(dir + "/points.yaml");
  EXPECT_EQ("base_link", points["frame"].as<std::string>());
  ASSERT_EQ(9u, points["points"].size());
  for (int id = 1; id <= 9; ++id)
  {
    const YAML::Node p = points["points"][id - 1];
    EXPECT_EQ(id, p["id"].as<int>());
    EXPECT_NEAR(pixels[id].first, p["u"].as<double>(), 1e-9);
    EXPECT_NEAR(pixels[id].second, p["v"].as<double>(), 1e-9);
    EXPECT_NEAR(expected[id][0], p["x"].as<double>(), 2e-6) << "id " << id;
    EXPECT_NEAR(expected[id][1], p["y"].as<double>(), 2e-6) << "id " << id;
    EXPECT_NEAR(0.0, p["z"].as<double>(), 2e-6) << "id " << id;
  }
  const YAML::Node mount = YAML::LoadFile(dir + "/mount.yaml");
  EXPECT_EQ("base_link", mount["parent_frame"].as<std::string>());
  EXPECT_NEAR(kMount.x, mount["x"].as<double>(), 1e-4);
  EXPECT_NEAR(kMount.y, mount["y"].as<double>(), 1e-4);
  EXPECT_NEAR(kMount.z, mount["z"].as<double>(), 1e-4);
  EXPECT_NEAR(kMount.roll, mount["roll"].as<double>(), 1e-4);
  EXPECT_NEAR(kMount.pitch, mount["pitch"].as<double>(), 1e-4);
  EXPECT_NEAR(kMount.yaw, mount["yaw"].as<double>(), 1e-4);
  EXPECT_NE(std::string::npos, tool.output().find("parent_frame:=base_link")) << tool.output();
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "clicked_points_test", ros::init_options::AnonymousName);
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
