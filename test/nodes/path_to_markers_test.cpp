// path_to_markers: on a known, unevenly sampled path the markers are exactly the spacing core's
// arrows and destination (ARROW markers with tail/tip points and the four sizes, a CYLINDER at the
// destination); a shorter path deletes the arrows it no longer has, an empty path clears all;
// the path is transformed into ~target_frame with tf; without tf nothing is published; NaN poses
// are dropped; bad parameters are replaced or clamped.
//
// path_to_markers.test starts four instances (exact, paper + target_frame map, no tf, bad
// parameters); this test publishes paths to them and replays the MarkerArrays they publish on a
// model of rviz's marker display (ADD/MODIFY, DELETE, DELETEALL), then compares.

#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/LinearMath/Transform.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "rviz_projector/core/path_spacer.h"

namespace
{
using visualization_msgs::Marker;
using visualization_msgs::MarkerArray;
using rviz_projector::SpacedPath;
using rviz_projector::SpacingMode;
using rviz_projector::SpacingParameters;
using rviz_projector::Vec2;

constexpr double kTolerance = 1e-9;
constexpr double kArrowLift = 0.001;  // arrows sit this much above the circle (as the display)

/// Unevenly sampled, curved, with a duplicate pose: what a grid planner publishes. Start -> goal.
const std::vector<Vec2> kPath = {{0.0, 0.0},  {0.05, 0.0}, {0.21, 0.01}, {0.22, 0.01}, {0.22, 0.01},
                                 {0.5, 0.1},  {0.9, 0.3},  {1.0, 0.35},  {1.3, 0.6},   {1.31, 0.62},
                                 {1.6, 0.9},  {1.75, 0.93}, {2.0, 1.0}};

nav_msgs::Path makePath(const std::vector<Vec2>& points, const std::string& frame)
{
  static std::uint32_t sequence = 0;
  nav_msgs::Path path;
  path.header.frame_id = frame;
  path.header.stamp = ros::Time::now() + ros::Duration(0, ++sequence);  // unique per path
  for (const Vec2& p : points)
  {
    geometry_msgs::PoseStamped pose;
    pose.header = path.header;
    pose.pose.position.x = p.x;
    pose.pose.position.y = p.y;
    pose.pose.position.z = 0.3;  // ignored: markers lie at ~height
    pose.pose.orientation.w = 1.0;
    path.poses.push_back(pose);
  }
  return path;
}

/// What rviz's Marker display shows after a sequence of MarkerArrays.
class MarkerScene
{
public:
  void apply(const MarkerArray& array)
  {
    for (const Marker& m : array.markers)
    {
      if (m.action == Marker::DELETEALL)
      {
        markers_.clear();
      }
      else if (m.action == Marker::DELETE)
      {
        markers_.erase({m.ns, m.id});
      }
      else
      {
        markers_[{m.ns, m.id}] = m;
      }
    }
  }
  std::size_t count(const std::string& ns) const
  {
    std::size_t n = 0;
    for (const auto& entry : markers_)
    {
      n += entry.first.first == ns ? 1 : 0;
    }
    return n;
  }
  std::size_t size() const { return markers_.size(); }
  const Marker* find(const std::string& ns, int id) const
  {
    const auto it = markers_.find({ns, id});
    return it == markers_.end() ? nullptr : &it->second;
  }

private:
  std::map<std::pair<std::string, int>, Marker> markers_;
};

/// One path_to_markers instance: its input, its output, and the scene its output builds.
class NodeUnderTest
{
public:
  explicit NodeUnderTest(const std::string& prefix)
  {
    ros::NodeHandle nh;
    path_pub_ = nh.advertise<nav_msgs::Path>(prefix + "/path", 1);
    markers_sub_ = nh.subscribe(prefix + "/markers", 10, &NodeUnderTest::onMarkers, this);
  }

  bool connected(double timeout = 15.0)
  {
    return waitFor([this] { return path_pub_.getNumSubscribers() > 0 && markers_sub_.getNumPublishers() > 0; },
                   timeout);
  }

  /// Publishes a path and waits for the MarkerArray it causes (its markers carry the path's stamp,
  /// which tells it from a latched array of an earlier test); false if none came.
  bool send(const nav_msgs::Path& path, double timeout = 10.0)
  {
    const std::size_t before = arrays_.size();
    path_pub_.publish(path);
    return waitFor(
        [this, before, &path] {
          for (std::size_t i = before; i < arrays_.size(); ++i)
          {
            const auto& markers = arrays_[i].markers;
            if (markers.empty() || markers.front().header.stamp == path.header.stamp)
            {
              return true;
            }
          }
          return false;
        },
        timeout);
  }

  /// Publishes a path and checks that nothing comes back within `wait` seconds.
  bool sendExpectingNothing(const nav_msgs::Path& path, double wait)
  {
    const std::size_t before = arrays_.size();
    path_pub_.publish(path);
    waitFor([] { return false; }, wait);
    return arrays_.size() == before;
  }

  const MarkerArray& last() const { return arrays_.back(); }
  const std::vector<MarkerArray>& arrays() const { return arrays_; }
  const MarkerScene& scene() const { return scene_; }

private:
  void onMarkers(const MarkerArray& array)
  {
    arrays_.push_back(array);
    scene_.apply(array);
  }

  template <typename Condition>
  static bool waitFor(Condition condition, double timeout)
  {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline)
    {
      ros::spinOnce();
      if (condition())
      {
        return true;
      }
      ros::WallDuration(0.005).sleep();
    }
    ros::spinOnce();
    return condition();
  }

  ros::Publisher path_pub_;
  ros::Subscriber markers_sub_;
  std::vector<MarkerArray> arrays_;
  MarkerScene scene_;
};

/// The node's spacing parameters, read from the parameter server (single source: the .test file).
SpacingParameters parametersOf(const std::string& node)
{
  ros::NodeHandle pnh(node);
  SpacingParameters p;
  p.mode = pnh.param<std::string>("spacing_mode", "exact") == "paper" ? SpacingMode::Paper : SpacingMode::Exact;
  p.spacing = pnh.param("spacing", p.spacing);
  p.arrow.shaft_length = pnh.param("shaft_length", p.arrow.shaft_length);
  p.arrow.shaft_diameter = pnh.param("shaft_diameter", p.arrow.shaft_diameter);
  p.arrow.head_length = pnh.param("head_length", p.arrow.head_length);
  p.arrow.head_diameter = pnh.param("head_diameter", p.arrow.head_diameter);
  p.circle_diameter = pnh.param("circle_diameter", p.circle_diameter);
  return p;
}

void expectColor(const std::vector<double>& rgba, const std_msgs::ColorRGBA& c, const std::string& what)
{
  EXPECT_NEAR(rgba[0], c.r, 1e-6) << what;
  EXPECT_NEAR(rgba[1], c.g, 1e-6) << what;
  EXPECT_NEAR(rgba[2], c.b, 1e-6) << what;
  EXPECT_NEAR(rgba[3], c.a, 1e-6) << what;
}

/// The scene holds exactly the core's arrows and destination, drawn as path_to_markers promises.
void expectSceneMatches(const MarkerScene& scene, const SpacedPath& expected, const SpacingParameters& p,
                        double height, const std::string& frame)
{
  ASSERT_EQ(expected.arrows.size(), scene.count("arrows"));
  ASSERT_EQ(expected.has_destination ? 1u : 0u, scene.count("destination"));
  ASSERT_EQ(expected.arrows.size() + (expected.has_destination ? 1u : 0u), scene.size());
  for (std::size_t k = 0; k < expected.arrows.size(); ++k)
  {
    const Marker* m = scene.find("arrows", static_cast<int>(k));
    ASSERT_TRUE(m != nullptr) << "arrow " << k;
    EXPECT_EQ(frame, m->header.frame_id);
    EXPECT_EQ(Marker::ARROW, m->type);
    ASSERT_EQ(2u, m->points.size()) << "arrow " << k;
    EXPECT_NEAR(expected.arrows[k].tail.x, m->points[0].x, kTolerance) << "arrow " << k << " tail";
    EXPECT_NEAR(expected.arrows[k].tail.y, m->points[0].y, kTolerance) << "arrow " << k << " tail";
    EXPECT_NEAR(height + kArrowLift, m->points[0].z, kTolerance) << "arrow " << k << " tail";
    EXPECT_NEAR(expected.arrows[k].tip.x, m->points[1].x, kTolerance) << "arrow " << k << " tip";
    EXPECT_NEAR(expected.arrows[k].tip.y, m->points[1].y, kTolerance) << "arrow " << k << " tip";
    EXPECT_NEAR(height + kArrowLift, m->points[1].z, kTolerance) << "arrow " << k << " tip";
    EXPECT_DOUBLE_EQ(p.arrow.shaft_diameter, m->scale.x) << "arrow " << k;
    EXPECT_DOUBLE_EQ(p.arrow.head_diameter, m->scale.y) << "arrow " << k;
    EXPECT_DOUBLE_EQ(p.arrow.head_length, m->scale.z) << "arrow " << k;
    EXPECT_DOUBLE_EQ(1.0, m->pose.orientation.w);
  }
  if (expected.has_destination)
  {
    const Marker* c = scene.find("destination", 0);
    ASSERT_TRUE(c != nullptr);
    EXPECT_EQ(frame, c->header.frame_id);
    EXPECT_EQ(Marker::CYLINDER, c->type);
    EXPECT_NEAR(expected.destination.x, c->pose.position.x, kTolerance);
    EXPECT_NEAR(expected.destination.y, c->pose.position.y, kTolerance);
    EXPECT_NEAR(height, c->pose.position.z, kTolerance);
    EXPECT_DOUBLE_EQ(p.circle_diameter, c->scale.x);
    EXPECT_DOUBLE_EQ(p.circle_diameter, c->scale.y);
    EXPECT_GT(c->scale.z, 0.0);
    EXPECT_LT(c->scale.z, 0.01);
  }
}

std::vector<int> deletedIds(const MarkerArray& array, const std::string& ns)
{
  std::vector<int> ids;
  for (const Marker& m : array.markers)
  {
    if (m.action == Marker::DELETE && m.ns == ns)
    {
      ids.push_back(m.id);
    }
  }
  return ids;
}
}  // namespace

TEST(PathToMarkers, ExactModeMarkersAreTheCoresArrowsAndShorterAndEmptyPathsDelete)
{
  NodeUnderTest node("/exact");
  ASSERT_TRUE(node.connected());
  const SpacingParameters p = parametersOf("/exact_markers");
  ASSERT_EQ(SpacingMode::Exact, p.mode);
  ASSERT_DOUBLE_EQ(0.3, p.spacing);  // the .test file's values are read, not the defaults
  rviz_projector::PathSpacer spacer(p);
  const double height = 0.02;

  // The known path.
  ASSERT_TRUE(node.send(makePath(kPath, "odom")));
  EXPECT_EQ(Marker::DELETEALL, node.arrays().front().markers.front().action) << "first array starts clean";
  const SpacedPath full = spacer.space(kPath);
  ASSERT_GE(full.arrows.size(), 5u);
  expectSceneMatches(node.scene(), full, p, height, "odom");
  // Colours from the parameters ([r, g, b] gets alpha 1).
  expectColor({1.0, 0.5, 0.0, 1.0}, node.scene().find("arrows", 0)->color, "arrow colour");
  expectColor({0.0, 0.0, 1.0, 0.5}, node.scene().find("destination", 0)->color, "circle colour");

  // The robot advanced: the path's start is trimmed. Fewer arrows; the extra ones are deleted, and
  // the remaining ones stay where they were (Exact mode is anchored at the destination).
  const std::vector<Vec2> shorter(kPath.begin() + 8, kPath.end());
  ASSERT_TRUE(node.send(makePath(shorter, "odom")));
  const SpacedPath trimmed = spacer.space(shorter);
  ASSERT_GE(trimmed.arrows.size(), 1u);
  ASSERT_LT(trimmed.arrows.size(), full.arrows.size());
  expectSceneMatches(node.scene(), trimmed, p, height, "odom");
  std::vector<int> expected_deleted;
  for (std::size_t k = trimmed.arrows.size(); k < full.arrows.size(); ++k)
  {
    expected_deleted.push_back(static_cast<int>(k));
  }
  EXPECT_EQ(expected_deleted, deletedIds(node.last(), "arrows"));
  for (std::size_t k = 0; k < trimmed.arrows.size(); ++k)
  {
    EXPECT_NEAR(full.arrows[k].tip.x, trimmed.arrows[k].tip.x, 1e-12);
    EXPECT_NEAR(full.arrows[k].tip.y, trimmed.arrows[k].tip.y, 1e-12);
  }

  // An empty path clears everything.
  ASSERT_TRUE(node.send(makePath({}, "odom")));
  EXPECT_EQ(0u, node.scene().size());
  EXPECT_EQ(1u, deletedIds(node.last(), "destination").size());

  // And the full path brings everything back.
  ASSERT_TRUE(node.send(makePath(kPath, "odom")));
  expectSceneMatches(node.scene(), full, p, height, "odom");
}

TEST(PathToMarkers, NanPosesAreDropped)
{
  NodeUnderTest node("/exact");
  ASSERT_TRUE(node.connected());
  const SpacingParameters p = parametersOf("/exact_markers");
  rviz_projector::PathSpacer spacer(p);
  ASSERT_TRUE(node.send(makePath({}, "odom")));
  ASSERT_EQ(0u, node.scene().size());

  nav_msgs::Path path = makePath(kPath, "odom");
  geometry_msgs::PoseStamped bad = path.poses[4];
  bad.pose.position.x = std::numeric_limits<double>::quiet_NaN();
  path.poses.insert(path.poses.begin() + 4, bad);
  bad = path.poses[9];
  bad.pose.orientation.w = std::numeric_limits<double>::infinity();
  path.poses.insert(path.poses.begin() + 9, bad);
  ASSERT_TRUE(node.send(path));
  expectSceneMatches(node.scene(), spacer.space(kPath), p, 0.02, "odom");
}

TEST(PathToMarkers, PaperModeInTargetFrameThroughTf)
{
  // map -> odom: shifted and turned.
  tf2_ros::StaticTransformBroadcaster broadcaster;
  tf2::Quaternion q;
  q.setRPY(0.0, 0.0, 0.3);
  const tf2::Transform map_from_odom(q, tf2::Vector3(1.0, -0.5, 0.0));
  geometry_msgs::TransformStamped t;
  t.header.stamp = ros::Time::now();
  t.header.frame_id = "map";
  t.child_frame_id = "odom";
  t.transform.translation.x = 1.0;
  t.transform.translation.y = -0.5;
  t.transform.rotation.x = q.x();
  t.transform.rotation.y = q.y();
  t.transform.rotation.z = q.z();
  t.transform.rotation.w = q.w();
  broadcaster.sendTransform(t);

  NodeUnderTest node("/paper");
  ASSERT_TRUE(node.connected());
  const SpacingParameters p = parametersOf("/paper_markers");
  ASSERT_EQ(SpacingMode::Paper, p.mode);

  std::vector<Vec2> in_map;
  for (const Vec2& v : kPath)
  {
    const tf2::Vector3 m = map_from_odom * tf2::Vector3(v.x, v.y, 0.3);
    in_map.push_back({m.x(), m.y()});
  }
  rviz_projector::PathSpacer spacer(p);
  const SpacedPath expected = spacer.space(in_map);
  ASSERT_GE(expected.arrows.size(), 3u);

  ASSERT_TRUE(node.send(makePath(kPath, "odom")));
  // Tolerance: tf2 and the core compose the rotation in different orders.
  ASSERT_EQ(expected.arrows.size(), node.scene().count("arrows"));
  for (std::size_t k = 0; k < expected.arrows.size(); ++k)
  {
    const Marker* m = node.scene().find("arrows", static_cast<int>(k));
    ASSERT_TRUE(m != nullptr);
    EXPECT_EQ("map", m->header.frame_id);
    EXPECT_NEAR(expected.arrows[k].tail.x, m->points[0].x, 1e-9);
    EXPECT_NEAR(expected.arrows[k].tail.y, m->points[0].y, 1e-9);
    EXPECT_NEAR(expected.arrows[k].tip.x, m->points[1].x, 1e-9);
    EXPECT_NEAR(expected.arrows[k].tip.y, m->points[1].y, 1e-9);
    EXPECT_DOUBLE_EQ(0.06, m->scale.x);
    EXPECT_DOUBLE_EQ(0.08, m->scale.y);
    EXPECT_DOUBLE_EQ(0.08, m->scale.z);
  }
  const Marker* circle = node.scene().find("destination", 0);
  ASSERT_TRUE(circle != nullptr);
  EXPECT_NEAR(expected.destination.x, circle->pose.position.x, 1e-9);
  EXPECT_NEAR(expected.destination.y, circle->pose.position.y, 1e-9);
  EXPECT_DOUBLE_EQ(0.12, circle->scale.x);
  EXPECT_NEAR(0.01, circle->pose.position.z, kTolerance);  // default ~height
  // Default colours: the display's magenta arrows and green circle.
  expectColor({1, 0, 1, 1}, node.scene().find("arrows", 0)->color, "arrow colour");
  expectColor({0, 1, 0, 1}, circle->color, "circle colour");
}

TEST(PathToMarkers, NoTransformNoMarkersButAnEmptyPathStillClears)
{
  NodeUnderTest node("/no_tf");
  ASSERT_TRUE(node.connected());
  EXPECT_TRUE(node.sendExpectingNothing(makePath(kPath, "odom"), 1.0));
  ASSERT_TRUE(node.send(makePath({}, "odom")));
  EXPECT_EQ(0u, node.scene().size());
}

TEST(PathToMarkers, BadParametersAreClampedOrReplaced)
{
  NodeUnderTest node("/bad_params");
  ASSERT_TRUE(node.connected());
  // shaft_diameter -1 and head_length 0 -> clamped to the smallest size (5 mm); spacing_mode
  // "sideways" -> exact; arrow_color "red" -> the default magenta; circle_color out of 0..1 ->
  // clamped; the rest default.
  SpacingParameters p;
  p.mode = SpacingMode::Exact;
  p.arrow.shaft_diameter = 0.005;
  p.arrow.head_length = 0.005;
  rviz_projector::PathSpacer spacer(p);
  ASSERT_TRUE(node.send(makePath(kPath, "odom")));
  expectSceneMatches(node.scene(), spacer.space(kPath), p, 0.01, "odom");
  expectColor({1, 0, 1, 1}, node.scene().find("arrows", 0)->color, "arrow colour");
  expectColor({1, 0, 0.5, 1}, node.scene().find("destination", 0)->color, "circle colour");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "path_to_markers_test", ros::init_options::AnonymousName);
  ros::NodeHandle nh;  // keeps the node alive for the whole run
  return RUN_ALL_TESTS();
}
