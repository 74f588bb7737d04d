// ProjectedPath in a real rviz: created through pluginlib by class name, fed through its topic,
// checked by the arrows it holds, its statuses and the pixels of a rendered top-down view.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include <QDir>
#include <QTemporaryDir>
#include <nav_msgs/Path.h>
#include <rviz/config.h>
#include <rviz/display_group.h>
#include <rviz/display.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>
#include <rviz/yaml_config_writer.h>

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/ros_clock.h"
#include "rviz_test_fixture.h"

using rviz_projector::ProjectedPathDisplay;
using rviz_projector_test::describe;
using rviz_projector_test::RvizInstance;
using rviz_projector_test::sameColour;
using rviz_projector_test::Status;

namespace
{
constexpr const char* kTopic = "/test/plan";
const QRgb kMagenta = qRgb(255, 0, 255);
const QRgb kGreen = qRgb(0, 255, 0);

/// Straight path along +x of `frame` from 0 to `length`, unevenly sampled.
nav_msgs::Path straightPath(const std::string& frame, double length)
{
  nav_msgs::Path path;
  path.header.frame_id = frame;
  path.header.stamp = ros::Time(0);
  const double steps[] = {0.05, 0.013, 0.11, 0.07};
  double x = 0.0;
  for (int i = 0;; ++i)
  {
    geometry_msgs::PoseStamped pose;
    pose.header = path.header;
    pose.pose.position.x = x;
    pose.pose.orientation.w = 1.0;
    path.poses.push_back(pose);
    if (x >= length)
    {
      break;
    }
    x = std::min(length, x + steps[i % 4]);
  }
  return path;
}

class ProjectedPathTest : public rviz_projector_test::RvizTest
{
protected:
  void SetUp() override
  {
    RvizTest::SetUp();
    // odom sits at (1, 0.5) in map, turned 90 degrees: odom's +x is map's +y.
    publishStaticTransform("map", "odom", 1.0, 0.5, 0.0, M_PI / 2);
    publisher_ = nh_.advertise<nav_msgs::Path>(kTopic, 1, true);
    display_ = addPathDisplay(*rviz_);
  }

  ProjectedPathDisplay* addPathDisplay(RvizInstance& rviz)
  {
    rviz::Display* display = rviz.addDisplay("rviz_projector/ProjectedPath", "Projected path");
    auto* path_display = dynamic_cast<ProjectedPathDisplay*>(display);
    EXPECT_NE(path_display, nullptr) << "pluginlib did not give a ProjectedPathDisplay";
    if (path_display)
    {
      path_display->subProp("Topic")->setValue(kTopic);
      path_display->subProp("Spacing")->setValue(0.5);
      path_display->subProp("Shaft length")->setValue(0.2);
      path_display->subProp("Head length")->setValue(0.1);
      path_display->subProp("Shaft diameter")->setValue(0.08);
      path_display->subProp("Head diameter")->setValue(0.2);
      path_display->subProp("Destination circle diameter")->setValue(0.3);
    }
    return path_display;
  }

  void publishAndWait(const nav_msgs::Path& path, std::size_t arrows)
  {
    publisher_.publish(path);
    ASSERT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == arrows && received(); }))
        << "got " << display_->spacedPath().arrows.size() << " arrows";
  }

  bool received() { return statusOf(display_, "Path").text != "No path received yet"; }

  ros::Publisher publisher_;
  ProjectedPathDisplay* display_ = nullptr;
};
}  // namespace

TEST_F(ProjectedPathTest, CreatedThroughPluginlibWithDefaults)
{
  ASSERT_NE(display_, nullptr);
  rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectedPath", "defaults");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->subProp("Topic")->getValue().toString().toStdString(), "/move_base/TrajectoryPlannerROS/global_plan");
  EXPECT_EQ(d->subProp("Spacing mode")->getValue().toString().toStdString(), "Exact");
  EXPECT_EQ(d->subProp("Style")->getValue().toString().toStdString(), "Flat");
  const Status s = statusOf(d, "Path");
  EXPECT_TRUE(s.present);
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_EQ(s.text.toStdString(), "No path received yet");
}

TEST_F(ProjectedPathTest, ArrowsLandAtTheirPositionsInTheFixedFrame)
{
  publishAndWait(straightPath("odom", 3.05), 6);
  const auto& spaced = display_->spacedPath();
  // Destination: odom (3.05, 0) -> map (1, 3.55). First tip 0.15 + 0.05 = 0.2 m back along the
  // path, then every 0.5 m; tails 0.3 m behind their tips; 0.2 + 0.5 k + 0.3 <= 3.05 gives 6.
  // Odom +x is map +y.
  EXPECT_NEAR(spaced.destination.x, 1.0, 1e-6);
  EXPECT_NEAR(spaced.destination.y, 3.55, 1e-6);
  for (std::size_t k = 0; k < spaced.arrows.size(); ++k)
  {
    EXPECT_NEAR(spaced.arrows[k].tip.x, 1.0, 1e-6);
    EXPECT_NEAR(spaced.arrows[k].tip.y, 3.35 - 0.5 * k, 1e-6) << k;
    EXPECT_NEAR(spaced.arrows[k].tail.y, 3.05 - 0.5 * k, 1e-6) << k;
  }
  EXPECT_EQ(display_->arrowTriangleCount(), 6u * 3u);
  EXPECT_GT(display_->circleTriangleCount(), 16u);
  const Status s = statusOf(display_, "Path");
  EXPECT_EQ(s.level, rviz::StatusProperty::Ok);
  EXPECT_EQ(s.text.toStdString(), "6 arrows on 3.05 m of path");
}

TEST_F(ProjectedPathTest, MeshesAreBuiltOncePerPathNotPerFrame)
{
  publishAndWait(straightPath("odom", 3.05), 6);
  const std::size_t builds = display_->meshBuilds();
  ASSERT_TRUE(waitForMainViewFrames(15));  // rviz updates its displays and renders its view 15 times
  rviz_->renderMainView();
  EXPECT_EQ(display_->meshBuilds(), builds) << "rebuilt without a new path or property change";
  display_->subProp("Arrow color")->setValue(QColor(0, 0, 255));
  EXPECT_EQ(display_->meshBuilds(), builds + 1);
  ASSERT_TRUE(waitForMainViewFrames(10));
  EXPECT_EQ(display_->meshBuilds(), builds + 1);
}

TEST_F(ProjectedPathTest, RenderedTopDownViewShowsArrowsAndCircle)
{
  publishAndWait(straightPath("odom", 3.05), 6);
  rviz_->setTopDownView(1.0, 2.0, 100.0);  // 1 cm per pixel; the path runs up the middle
  ASSERT_TRUE(waitForMainViewFrames(2));  // the view controller moves the camera in rviz's update
  const QImage image = rviz_->renderMainView();
  ASSERT_FALSE(image.isNull());
  const auto& arrows = display_->spacedPath().arrows;
  const QRgb background = image.pixel(5, 5);
  EXPECT_FALSE(sameColour(background, kMagenta));
  for (std::size_t k = 0; k < arrows.size(); ++k)
  {
    // Middle of the shaft (tail + 0.1 m) and middle of the head's base area.
    const QPoint shaft = rviz_->topDownPixel(1.0, arrows[k].tail.y + 0.1);
    const QPoint head = rviz_->topDownPixel(1.0, arrows[k].tip.y - 0.03);
    EXPECT_TRUE(sameColour(image.pixel(shaft), kMagenta)) << "arrow " << k << " shaft " << describe(image.pixel(shaft));
    EXPECT_TRUE(sameColour(image.pixel(head), kMagenta)) << "arrow " << k << " head " << describe(image.pixel(head));
    // Between this arrow's tail and the next tip (0.2 m gap): floor.
    const QPoint gap = rviz_->topDownPixel(1.0, arrows[k].tail.y - 0.1);
    EXPECT_FALSE(sameColour(image.pixel(gap), kMagenta)) << "gap after arrow " << k;
    // Beside the shaft, outside the head width.
    const QPoint beside = rviz_->topDownPixel(1.15, arrows[k].tail.y + 0.1);
    EXPECT_TRUE(sameColour(image.pixel(beside), background)) << "beside arrow " << k;
  }
  const QPoint goal = rviz_->topDownPixel(1.0, 3.55);
  EXPECT_TRUE(sameColour(image.pixel(goal), kGreen)) << describe(image.pixel(goal));
  const QPoint beyond_goal = rviz_->topDownPixel(1.0, 3.55 + 0.2);
  EXPECT_FALSE(sameColour(image.pixel(beyond_goal), kGreen));
}

TEST_F(ProjectedPathTest, PropertyChangesRedrawWithoutANewMessage)
{
  publishAndWait(straightPath("odom", 3.05), 6);
  rviz_->setTopDownView(1.0, 2.0, 100.0);
  display_->subProp("Spacing")->setValue(0.875);  // 0.2 + 0.875 k + 0.3 <= 3.05 -> 3 arrows
  ASSERT_EQ(display_->spacedPath().arrows.size(), 3u);
  EXPECT_NEAR(display_->spacedPath().arrows[1].tip.y, 3.35 - 0.875, 1e-6);

  display_->subProp("Arrow color")->setValue(QColor(0, 0, 255));
  const QPoint shaft = rviz_->topDownPixel(1.0, display_->spacedPath().arrows[1].tail.y + 0.1);
  QImage image;
  waitFor([&] {
    image = rviz_->renderMainView();
    return sameColour(image.pixel(shaft), qRgb(0, 0, 255));
  });
  EXPECT_TRUE(sameColour(image.pixel(shaft), qRgb(0, 0, 255))) << describe(image.pixel(shaft));
  // Where arrow 1 used to be with 0.5 m spacing (tip 2.85, tail 2.55) is floor now.
  const QPoint old_arrow = rviz_->topDownPixel(1.0, 2.65);
  EXPECT_FALSE(sameColour(image.pixel(old_arrow), qRgb(0, 0, 255)));

  display_->subProp("Style")->setValue("3D");
  EXPECT_EQ(display_->arrowTriangleCount(), 3u * 5u * 16u);
  // Shaded, so not exactly the colour, but clearly blue and still in the same place.
  const QRgb shaded = rviz_->renderMainView().pixel(shaft);
  EXPECT_GT(qBlue(shaded), 2 * std::max(qRed(shaded), qGreen(shaded)) + 40) << describe(shaded);
  // Half transparent: the floor shows through (blue blended half and half with what is below).
  display_->subProp("Style")->setValue("Flat");
  display_->subProp("Alpha")->setValue(0.0);  // invisible: what lies under the shaft
  const QRgb floor = rviz_->renderMainView().pixel(shaft);
  display_->subProp("Alpha")->setValue(0.5);
  const QRgb blended = rviz_->renderMainView().pixel(shaft);
  EXPECT_NEAR(qBlue(blended), (255 + qBlue(floor)) / 2, 12) << describe(blended) << " over " << describe(floor);
  EXPECT_NEAR(qRed(blended), qRed(floor) / 2, 12) << describe(blended) << " over " << describe(floor);
  display_->subProp("Alpha")->setValue(1.0);
  display_->subProp("Spacing mode")->setValue("Paper");
  EXPECT_GT(display_->spacedPath().arrows.size(), 0u);
}

TEST_F(ProjectedPathTest, SpacingShorterThanAnArrowIsFlagged)
{
  display_->subProp("Spacing")->setValue(0.2);  // arrow is 0.3 m long
  const Status s = statusOf(display_, "Geometry");
  ASSERT_TRUE(s.present);
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_NE(s.text.indexOf("shorter than an arrow"), -1) << s.text.toStdString();
  display_->subProp("Spacing")->setValue(1.0);
  EXPECT_FALSE(statusOf(display_, "Geometry").present);
  // Nonsense sizes are clamped to the minimum, never zero or negative.
  display_->subProp("Head length")->setValue(-3.0);
  EXPECT_GT(display_->subProp("Head length")->getValue().toDouble(), 0.0);
  display_->subProp("Shaft diameter")->setValue(std::numeric_limits<double>::quiet_NaN());
  EXPECT_GT(display_->subProp("Shaft diameter")->getValue().toDouble(), 0.0);
}

TEST_F(ProjectedPathTest, ConfigRoundTripRestoresPropertiesAndArrows)
{
  display_->subProp("Spacing")->setValue(0.75);
  display_->subProp("Arrow color")->setValue(QColor(10, 200, 30));
  display_->subProp("Style")->setValue("3D");
  display_->subProp("Height above floor")->setValue(0.05);
  publishAndWait(straightPath("odom", 3.05), 4);

  QTemporaryDir dir;
  const QString file = dir.path() + "/saved.rviz";
  rviz::Config saved;
  rviz_->manager()->save(saved);
  rviz::YamlConfigWriter().writeFile(saved, file);
  const std::vector<rviz_projector::Arrow> before = display_->spacedPath().arrows;
  std::map<std::string, std::string> properties;
  const char* names[] = {"Topic", "Spacing mode", "Spacing", "Shaft length", "Shaft diameter", "Head length",
                         "Head diameter", "Destination circle diameter", "Arrow color", "Circle color", "Alpha",
                         "Height above floor", "Style"};
  for (const char* name : names)
  {
    properties[name] = display_->subProp(name)->getValue().toString().toStdString();
  }
  rviz_.reset();  // close this rviz before starting the next

  RvizInstance fresh(320, 240);
  rviz::Config loaded;
  rviz::YamlConfigReader reader;
  reader.readFile(loaded, file);
  ASSERT_FALSE(reader.error()) << reader.errorMessage().toStdString();
  fresh.manager()->load(loaded);
  rviz::Display* d = nullptr;
  ASSERT_TRUE(waitFor([&] {
    for (int i = 0; i < fresh.manager()->getRootDisplayGroup()->numDisplays(); ++i)
    {
      auto* p = dynamic_cast<ProjectedPathDisplay*>(fresh.manager()->getRootDisplayGroup()->getDisplayAt(i));
      if (p && p->spacedPath().arrows.size() == 4)
      {
        d = p;
      }
    }
    return d != nullptr;
  }));
  for (const char* name : names)
  {
    EXPECT_EQ(d->subProp(name)->getValue().toString().toStdString(), properties[name]) << name;
  }
  EXPECT_EQ(properties["Spacing"], "0.75");
  EXPECT_EQ(properties["Style"], "3D");
  const auto& a = dynamic_cast<ProjectedPathDisplay*>(d)->spacedPath().arrows;
  const auto& b = before;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_DOUBLE_EQ(a[k].tip.x, b[k].tip.x);
    EXPECT_DOUBLE_EQ(a[k].tip.y, b[k].tip.y);
    EXPECT_DOUBLE_EQ(a[k].tail.y, b[k].tail.y);
  }
}

TEST_F(ProjectedPathTest, ResetKeepsTheSubscriptionOfAnUnlatchedPlanner)
{
  // Issue 23 (found by the replay test): rviz resets every display when ROS time jumps back (a bag
  // loop). Subscribing again there lost every plan published before the new connection stood: the
  // first plan of each loop. An unlatched planner keeps its subscription; a latched plan comes
  // back after a Reset by subscribing again.
  ros::Publisher planner = nh_.advertise<nav_msgs::Path>("/test/unlatched_plan", 1, false);
  display_->subProp("Topic")->setValue("/test/unlatched_plan");
  ASSERT_TRUE(waitFor([&] { return planner.getNumSubscribers() > 0; }));
  planner.publish(straightPath("odom", 3.05));
  ASSERT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == 6; }));
  rviz_->manager()->getRootDisplayGroup()->reset();
  ASSERT_TRUE(waitFor([&] { return display_->spacedPath().arrows.empty(); })) << "Reset clears the drawing";
  planner.publish(straightPath("odom", 2.05));  // at once: no time to connect again
  EXPECT_TRUE(waitFor([&] { return !display_->spacedPath().arrows.empty(); }))
      << "the plan sent right after the Reset was lost";
  // A latched plan comes back by itself after a Reset.
  display_->subProp("Topic")->setValue(kTopic);
  publishAndWait(straightPath("odom", 3.05), 6);
  rviz_->manager()->getRootDisplayGroup()->reset();
  EXPECT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == 6 && received(); }))
      << "the latched plan did not come back after Reset";
}

TEST_F(ProjectedPathTest, APlanReplayedAsRosTimeJumpsBackIsDrawnThoughRvizResetsLateOrTfIsCleared)
{
  // A bag looping (`rosbag play -l`; seen in CI on a loaded machine): ROS time jumps back and the
  // bag replays its first transforms and plan. Two things lost that plan, and the floor stayed dark
  // for a whole planning period:
  //   A. rviz notices the jump at its next update, a frame late, and resets every display (the plan
  //      already drawn, or waiting in the tf filter, was dropped);
  //   B. tf2's listener clears tf at the first transform after the jump, which can come after the
  //      transforms replayed before the plan: only later transforms remain, and the plan could never
  //      be transformed at its stamp.
  // rviz's update is stopped: the test makes each happen at the worst moment, by hand.
  rviz_->manager()->stopUpdate();
  const ros::Time t0 = rviz_projector_test::monotonicTestStart();
  auto buffer = rviz_->manager()->getTF2BufferPtr();
  const auto mapToOdom = [&](double t) {
    // A frame of its own, as the fixture's odom (at (1, 0.5) in map turned 90 degrees), but moving
    // (tf keeps a static transform through a clear).
    geometry_msgs::TransformStamped s = rviz_projector_test::stampedTransform(
        "map", "loop_odom", 1.0, 0.5, 0.0, {0.0, 0.0, std::sin(M_PI / 4), std::cos(M_PI / 4)});
    s.header.stamp = t0 + ros::Duration(t);
    buffer->setTransform(s, "projected_path_test");
  };
  ros::Publisher planner = nh_.advertise<nav_msgs::Path>("/test/looping_plan", 1, false);
  display_->subProp("Topic")->setValue("/test/looping_plan");
  ASSERT_TRUE(waitFor([&] { return planner.getNumSubscribers() > 0; }));
  const auto plan = [&](double length, double t) {
    nav_msgs::Path path = straightPath("loop_odom", length);
    path.header.stamp = t0 + ros::Duration(t);
    planner.publish(path);
  };
  const auto endOfPass = [&] {  // the end of a pass: a plan of 6 arrows at t0 + 10 s
    ros::Time::setNow(t0 + ros::Duration(10.0));
    buffer->clear();
    mapToOdom(9.9);
    mapToOdom(10.0);
    plan(3.05, 10.0);
    return waitFor([&] { return display_->spacedPath().arrows.size() == 6; });
  };
  const auto transformText = [&] { return statusOf(display_, "Transform").text.toStdString(); };

  // A: the loop's first plan (4 arrows) is drawn, then rviz resets: drawn again from the same plan.
  ASSERT_TRUE(endOfPass());
  ros::Time::setNow(t0 + ros::Duration(0.05));
  buffer->clear();
  mapToOdom(0.0);
  mapToOdom(0.04);
  plan(2.05, 0.03);
  ASSERT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == 4; }))
      << "the loop's first plan was not drawn: " << display_->spacedPath().arrows.size() << " arrows";
  rviz_->manager()->resetTime();
  EXPECT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == 4; }))
      << "A: the plan of the new pass was lost at rviz's late reset: " << display_->spacedPath().arrows.size()
      << " arrows; " << transformText();
  EXPECT_EQ(transformText(), "Transform OK");

  // B: tf cleared after the transforms before the plan came; only later ones arrive.
  ASSERT_TRUE(endOfPass());
  ros::Time::setNow(t0 + ros::Duration(0.05));
  mapToOdom(0.0);
  mapToOdom(0.02);
  buffer->clear();  // tf2's listener, at its first transform after the jump
  plan(2.05, 0.03);
  mapToOdom(0.06);
  mapToOdom(0.08);
  EXPECT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == 4; }))
      << "B: the plan whose transforms were cleared was never drawn: " << display_->spacedPath().arrows.size()
      << " arrows; " << transformText();
  const Status transform = statusOf(display_, "Transform");
  EXPECT_EQ(transform.level, rviz::StatusProperty::Ok) << transformText();
  EXPECT_TRUE(transform.text.contains("newest transform")) << transformText();
  // Where it lies (the newest transform is the same here): loop_odom's +x is map's +y from (1, 0.5),
  // so the plan from x 0 to 2.05 runs along map x = 1, y from 0.5 to 2.55.
  for (const auto& arrow : display_->spacedPath().arrows)
  {
    EXPECT_NEAR(arrow.tip.x, 1.0, 1e-6);
    EXPECT_GE(arrow.tip.y, 0.5 - 1e-6);
    EXPECT_LE(arrow.tip.y, 2.55 + 1e-6);
  }

  // A plan of before a jump (stamped in the old timeline) is not drawn again by rviz's reset.
  ASSERT_TRUE(endOfPass());
  ros::Time::setNow(t0 + ros::Duration(0.5));  // the loop, no plan of the new pass yet
  ASSERT_TRUE(waitFor([&] { return rviz_projector::RosClock::shared().policy().justStartedOrJumpedBack(); }));
  rviz_->manager()->resetTime();
  EXPECT_FALSE(waitFor([&] { return !display_->spacedPath().arrows.empty(); }, 0.5))
      << "the plan of before the jump came back after rviz's reset";
  rviz_->manager()->startUpdate();
}

TEST_F(ProjectedPathTest, EmptyPathIsReportedAndClearsTheDrawing)
{
  publishAndWait(straightPath("odom", 3.05), 6);
  nav_msgs::Path empty;
  empty.header.frame_id = "odom";
  publisher_.publish(empty);
  ASSERT_TRUE(waitFor([&] { return statusOf(display_, "Path").text.startsWith("Empty path"); }));
  const Status s = statusOf(display_, "Path");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_EQ(s.text.toStdString(), "Empty path (no poses): nothing to draw");
  EXPECT_EQ(display_->arrowTriangleCount(), 0u);
  EXPECT_EQ(display_->circleTriangleCount(), 0u);
}

TEST_F(ProjectedPathTest, NanPosesAreDroppedWithAWarning)
{
  nav_msgs::Path path = straightPath("odom", 3.05);
  path.poses[3].pose.position.y = std::numeric_limits<double>::quiet_NaN();
  path.poses[7].pose.orientation.z = std::numeric_limits<double>::infinity();
  publishAndWait(path, 6);
  const Status s = statusOf(display_, "Path");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_EQ(s.text.toStdString(), "2 poses with NaN/Inf or out-of-range values dropped; 6 arrows drawn");

  nav_msgs::Path one = straightPath("odom", 0.0);
  ASSERT_EQ(one.poses.size(), 1u);
  publishAndWait(one, 0);
  EXPECT_EQ(display_->circleTriangleCount(), 48u);  // the destination circle alone
}

TEST_F(ProjectedPathTest, UnknownFrameIsReportedAndRecoversWhenTheFrameAppears)
{
  nav_msgs::Path path = straightPath("late_frame", 2.05);
  path.header.stamp = ros::Time::now();
  publisher_.publish(path);
  ASSERT_TRUE(waitFor([&] {
    const Status s = statusOf(display_, "Transform");
    return s.present && s.level == rviz::StatusProperty::Error;
  }));
  const Status s = statusOf(display_, "Transform");
  EXPECT_NE(s.text.indexOf("late_frame"), -1) << s.text.toStdString();
  EXPECT_EQ(display_->spacedPath().arrows.size(), 0u);
  // The frame shows up: the queued path goes through by itself.
  publishStaticTransform("map", "late_frame", 0.0, 0.0, 0.0, 0.0);
  publisher_.publish(path);
  ASSERT_TRUE(waitFor([&] { return display_->spacedPath().arrows.size() == 4; }, 8.0));
  EXPECT_EQ(statusOf(display_, "Transform").level, rviz::StatusProperty::Ok);
}

TEST_F(ProjectedPathTest, NonsenseInAConfigIsClampedAndReported)
{
  const char* yaml = R"(
Displays:
  - Class: rviz_projector/ProjectedPath
    Name: From a bad config
    Enabled: true
    Topic: /test/plan
    Spacing: -3
    Shaft length: abc
    Head length: .nan
    Head diameter: 1e9
    Alpha: 7
    Spacing mode: Fast
    Style: Neon
)";
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readString(config, yaml);
  ASSERT_FALSE(reader.error()) << reader.errorMessage().toStdString();
  rviz_->manager()->load(config);
  rviz::DisplayGroup* root = rviz_->manager()->getRootDisplayGroup();
  ASSERT_EQ(root->numDisplays(), 1);
  rviz::Display* d = root->getDisplayAt(0);
  EXPECT_NEAR(d->subProp("Spacing")->getValue().toDouble(), 0.01, 1e-6);
  EXPECT_NEAR(d->subProp("Shaft length")->getValue().toDouble(), 0.005, 1e-6);
  EXPECT_GT(d->subProp("Head length")->getValue().toDouble(), 0.0);
  EXPECT_NEAR(d->subProp("Head diameter")->getValue().toDouble(), 10.0, 1e-6);
  EXPECT_NEAR(d->subProp("Alpha")->getValue().toDouble(), 1.0, 1e-6);
  EXPECT_EQ(d->subProp("Spacing mode")->getValue().toString().toStdString(), "Exact");
  EXPECT_EQ(d->subProp("Style")->getValue().toString().toStdString(), "Flat");
  const Status s = statusOf(d, "Config");
  ASSERT_TRUE(s.present);
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  for (const char* name : {"Spacing: '-3'", "Shaft length: 'abc'", "Head length", "Head diameter: '1e9'", "Alpha: '7'",
                           "Spacing mode: 'Fast' -> Exact", "Style: 'Neon' -> Flat"})
  {
    EXPECT_NE(s.text.indexOf(name), -1) << name << " missing in: " << s.text.toStdString();
  }
  // And it still draws.
  publisher_.publish(straightPath("odom", 3.05));
  auto* path = dynamic_cast<ProjectedPathDisplay*>(d);
  ASSERT_NE(path, nullptr);
  EXPECT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); }));
}

TEST_F(ProjectedPathTest, FixedFrameChangeRedrawsTheLastPath)
{
  publishAndWait(straightPath("odom", 3.05), 6);
  rviz_->manager()->setFixedFrame("odom");
  // Redrawn from the last message, now in odom (where the path is a straight line along +x).
  ASSERT_TRUE(waitFor([&] { return display_->spacedPath().has_destination; }))
      << statusOf(display_, "Path").text.toStdString() << " / " << statusOf(display_, "Transform").text.toStdString();
  EXPECT_NEAR(display_->spacedPath().destination.x, 3.05, 1e-6);
  EXPECT_NEAR(display_->spacedPath().destination.y, 0.0, 1e-6);
  EXPECT_EQ(display_->spacedPath().arrows.size(), 6u);
}
