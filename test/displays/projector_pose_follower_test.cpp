// ProjectorPoseFollower: the pose from tf frame after frame, and when ProjectorCamera must show its
// Transform status anew (an Ok pose that stays Ok builds nothing). tf2_ros::Buffer without a node.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <geometry_msgs/TransformStamped.h>
#include <tf2_ros/buffer.h>

#include "rviz_projector/displays/projector_pose.h"

using rviz_projector::ProjectorPoseFollower;

namespace
{
geometry_msgs::TransformStamped transform(const std::string& child, double stamp, double x)
{
  geometry_msgs::TransformStamped t;
  t.header.frame_id = "map";
  t.header.stamp = ros::Time(stamp);
  t.child_frame_id = child;
  t.transform.translation.x = x;
  t.transform.rotation.w = 1.0;
  return t;
}
}  // namespace

TEST(ProjectorPoseFollower, OkPoseIsReportedOnceThenNotAgain)
{
  tf2_ros::Buffer tf(ros::Duration(10.0), false);
  tf.setTransform(transform("projector", 0.0, 1.5), "test", true);
  ProjectorPoseFollower follower;
  EXPECT_FALSE(follower.shown());
  ProjectorPoseFollower::Step step = follower.follow(tf, "map", "projector", 100.0, 1.0);
  EXPECT_TRUE(step.ok);
  EXPECT_TRUE(step.status_changed) << "first pose: the Ok status is shown";
  EXPECT_TRUE(step.problem.empty());
  EXPECT_DOUBLE_EQ(follower.pose().optical_to_fixed.translation().x, 1.5);
  step = follower.follow(tf, "map", "projector", 100.1, 1.0);
  EXPECT_TRUE(step.ok);
  EXPECT_FALSE(step.status_changed) << "still Ok: nothing to show";
  EXPECT_EQ(follower.tfAge(), 0.0) << "static transforms never age";
  follower.forget();  // rviz's Reset cleared the statuses
  EXPECT_FALSE(follower.shown());
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 100.2, 1.0).status_changed) << "raised again after Reset";
}

TEST(ProjectorPoseFollower, MissingAndStalePosesAreProblemsEveryFrame)
{
  tf2_ros::Buffer tf(ros::Duration(10.0), false);
  ProjectorPoseFollower follower;
  ProjectorPoseFollower::Step step = follower.follow(tf, "map", "projector", 100.0, 1.0);
  EXPECT_FALSE(step.ok);
  EXPECT_TRUE(step.status_changed);
  EXPECT_FALSE(step.problem.empty());
  EXPECT_TRUE(std::isnan(follower.tfAge())) << "no tf: no age";
  // A moving link last heard of at t = 100 s, looked at 5 s later with a 1 s TF timeout.
  tf.setTransform(transform("projector", 100.0, 2.0), "test", false);
  step = follower.follow(tf, "map", "projector", 105.0, 1.0);
  EXPECT_FALSE(step.ok) << "stale: blanked like a missing pose";
  EXPECT_TRUE(step.status_changed);
  EXPECT_NE(step.problem.find("projector"), std::string::npos) << step.problem;
  EXPECT_NEAR(follower.tfAge(), 5.0, 1e-9);
  // Fresh again: Ok, shown once.
  step = follower.follow(tf, "map", "projector", 100.5, 1.0);
  EXPECT_TRUE(step.ok);
  EXPECT_TRUE(step.status_changed);
  EXPECT_NEAR(follower.tfAge(), 0.5, 1e-9);
  EXPECT_FALSE(follower.follow(tf, "map", "projector", 100.6, 1.0).status_changed);
}

TEST(ProjectorPoseFollower, NewTfIsAlwaysLookedUpAndOldTfAgesWithoutIt)
{
  // The follower reuses its last lookup while tf has nothing new: what it shows must still be what
  // a fresh lookup gives (the raw transforms are the oracle), and the age must keep growing.
  tf2_ros::Buffer tf(ros::Duration(10.0), false);
  tf.setTransform(transform("projector", 100.0, 1.0), "test", false);
  ProjectorPoseFollower follower;
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 100.2, 1.0).ok);
  EXPECT_DOUBLE_EQ(follower.pose().optical_to_fixed.translation().x, 1.0);
  EXPECT_NEAR(follower.tfAge(), 0.2, 1e-9);
  // Nothing new: same pose, older; past the TF timeout it is stale.
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 100.5, 1.0).ok);
  EXPECT_NEAR(follower.tfAge(), 0.5, 1e-9);
  EXPECT_FALSE(follower.follow(tf, "map", "projector", 101.5, 1.0).ok) << "stale without new tf";
  // New tf: looked up at once, fresh again.
  tf.setTransform(transform("projector", 101.4, 3.0), "test", false);
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 101.5, 1.0).ok);
  EXPECT_DOUBLE_EQ(follower.pose().optical_to_fixed.translation().x, 3.0);
  EXPECT_NEAR(follower.pose().stamp, 101.4, 1e-9);
  // Another frame with no new tf is another lookup, not the old frame's pose.
  tf.setTransform(transform("other", 0.0, 7.0), "test", true);
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 101.5, 1.0).ok);
  EXPECT_TRUE(follower.follow(tf, "map", "other", 101.5, 1.0).ok);
  EXPECT_DOUBLE_EQ(follower.pose().optical_to_fixed.translation().x, 7.0);
  // A transform of a link that is not in the chain changes nothing shown.
  tf.setTransform(transform("unrelated", 101.5, 9.0), "test", false);
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 101.5, 1.0).ok);
  EXPECT_DOUBLE_EQ(follower.pose().optical_to_fixed.translation().x, 3.0);
}

TEST(ProjectorPoseFollower, AnotherBufferIsLookedUpAfresh)
{
  ProjectorPoseFollower follower;
  {
    tf2_ros::Buffer first(ros::Duration(10.0), false);
    first.setTransform(transform("projector", 0.0, 1.0), "test", true);
    EXPECT_TRUE(follower.follow(first, "map", "projector", 100.0, 1.0).ok);
  }
  tf2_ros::Buffer second(ros::Duration(10.0), false);
  second.setTransform(transform("projector", 0.0, 2.0), "test", true);
  EXPECT_TRUE(follower.follow(second, "map", "projector", 100.0, 1.0).ok);
  EXPECT_DOUBLE_EQ(follower.pose().optical_to_fixed.translation().x, 2.0);
}

TEST(ProjectorPoseFollower, TfFromBeforeABackwardJumpIsNeverFreshAndInvalidateDropsTheLookup)
{
  // Issue 23, defect 2: `rosbag play -l` makes ROS time jump back at each loop. tf stamped before
  // the jump lies in the future of the new time: it used to count as 0 s old, so TF timeout never
  // blanked it, and the cached lookup was kept.
  tf2_ros::Buffer tf(ros::Duration(300.0), false);
  tf.setTransform(transform("projector", 200.0, 1.0), "test", false);
  ProjectorPoseFollower follower;
  ASSERT_TRUE(follower.follow(tf, "map", "projector", 200.1, 1.0).ok);
  // The loop: ROS time is 100 s again; the buffer still holds the pose of 200 s.
  ProjectorPoseFollower::Step step = follower.follow(tf, "map", "projector", 100.0, 1.0);
  EXPECT_FALSE(step.ok) << "a pose 100 s in the future of ROS time was shown as fresh";
  EXPECT_NE(step.problem.find("ahead of ROS time"), std::string::npos) << step.problem;
  // Skew within the TF timeout is tolerated.
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 199.5, 1.0).ok);
  // rviz clears its buffer at the jump; the follower drops its cached lookup when told to.
  tf.clear();
  EXPECT_TRUE(follower.follow(tf, "map", "projector", 199.6, 1.0).ok) << "the cached lookup (no new tf signal)";
  follower.invalidate();
  EXPECT_FALSE(follower.follow(tf, "map", "projector", 100.0, 1.0).ok) << "the pre-jump pose was kept";
  tf.setTransform(transform("projector", 100.05, 2.0), "test", false);
  ASSERT_TRUE(follower.follow(tf, "map", "projector", 100.1, 1.0).ok);
  EXPECT_DOUBLE_EQ(follower.pose().optical_to_fixed.translation().x, 2.0);
}
