// main() of the rviz tests: ROS node + QApplication, then gtest.
#include <gtest/gtest.h>

#include <QApplication>
#include <ros/ros.h>

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "rviz_projector_test", ros::init_options::AnonymousName);
  QApplication app(argc, argv);
  ros::NodeHandle nh;  // keeps the node alive for the whole run
  return RUN_ALL_TESTS();
}
