// ProjectionMask's Acknowledge group (issue 25, part 4: "I have seen you") in a real rviz, judged
// on the projector's pixels: a person-sized cluster of a scan near the path gets an arc on the
// robot's side, where the test computes it by hand from the scan's raw fields (the cluster's mean
// and radius, the mask's Margin, Distance, Line width, the direction to the robot) and
// image_geometry's projection; nothing of it on the person's masked feet; none out of Range or with
// the group off; it fades linearly and is gone after Hold; a walking person keeps one track and
// the arc follows; bad input gives a status, not a crash; the group is saved and loaded, and an
// old config loads with it off. ROS time is simulated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <QColor>
#include <nav_msgs/Path.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/properties/property.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/buffer.h>

#include "projector_test_fixture.h"
#include "robustness_helpers.h"
#include "rviz_projector/displays/projection_mask_display.h"
#include "rviz_projector/displays/projector_camera_display.h"

using namespace rviz_projector_test;

namespace
{
/// With RP_TEST_SHOTS set (a folder), saves `image` there as NAME.png (the README's picture).
const QRgb kArc = qRgb(255, 255, 255);  // the Color property's default
constexpr double kLaserZ = 0.3;        // test_laser at (0, 0, 0.3) of map, yaw 0
constexpr double kMargin = 0.1;        // the mask's Margin (default)
constexpr double kDistance = 0.2;      // Distance (default)
constexpr double kWidth = 0.08;        // Line width (set)

/// A person seen by the laser: beams over `half_angle` either side of the direction to `centre`,
/// each returning 0.1 m short of it. `points` gets the returns' floor points computed from the
/// message's own (float) fields, as a LaserScan defines them.
sensor_msgs::LaserScan personScan(const Vec2& centre, const ros::Time& stamp, std::vector<Vec2>& points)
{
  sensor_msgs::LaserScan scan;
  scan.header.frame_id = "test_laser";
  scan.header.stamp = stamp;
  const double bearing = std::atan2(centre.y, centre.x);
  const int beams = 17;
  scan.angle_increment = 0.01f;
  scan.angle_min = static_cast<float>(bearing - 0.08);
  scan.angle_max = scan.angle_min + scan.angle_increment * (beams - 1);
  scan.range_min = 0.05f;
  scan.range_max = 10.0f;
  scan.ranges.assign(beams, static_cast<float>(std::hypot(centre.x, centre.y) - 0.1));
  points.clear();
  for (int i = 0; i < beams; ++i)
  {
    const double a = double(scan.angle_min) + i * double(scan.angle_increment);
    points.push_back({scan.ranges[i] * std::cos(a), scan.ranges[i] * std::sin(a)});
  }
  return scan;
}

/// The arc by hand: the cluster's mean and radius, the masked feet (radius + Margin x sqrt 2: the
/// corner of a square column), the arc's middle radius, the unit vector towards the robot.
struct ArcOracle
{
  Vec2 mean;
  double radius = 0.0;
  double middle = 0.0;
  Vec2 towards_robot;

  ArcOracle(const std::vector<Vec2>& points, const Vec2& robot)
  {
    for (const Vec2& p : points)
    {
      mean.x += p.x / points.size();
      mean.y += p.y / points.size();
    }
    for (const Vec2& p : points)
    {
      radius = std::max(radius, std::hypot(p.x - mean.x, p.y - mean.y));
    }
    middle = radius + kMargin * std::sqrt(2.0) + kDistance + 0.5 * kWidth;
    const double d = std::hypot(robot.x - mean.x, robot.y - mean.y);
    towards_robot = {(robot.x - mean.x) / d, (robot.y - mean.y) / d};
  }
  /// A point of the arc's middle line, `angle` radians from the direction to the robot.
  Vec2 at(double angle) const
  {
    const double c = std::cos(angle), s = std::sin(angle);
    const Vec2 u{towards_robot.x * c - towards_robot.y * s, towards_robot.x * s + towards_robot.y * c};
    return {mean.x + middle * u.x, mean.y + middle * u.y};
  }
};

class AcknowledgeTest : public ProjectorSceneTest
{
protected:
  void SetUp() override
  {
    ProjectorSceneTest::SetUp();
    start_ = monotonicTestStart();
    ros::Time::setNow(start_);
    publishStaticTransform("map", "test_laser", 0.0, 0.0, kLaserZ, 0.0);
    publishStaticTransform("map", "test_base", 0.0, 0.0, 0.0, 0.0);
    scan_pub_ = nh_.advertise<sensor_msgs::LaserScan>("/test/scan", 5);
    plan_pub_ = nh_.advertise<nav_msgs::Path>("/test/ack_plan", 1, true);
    rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectionMask", "Projection mask");
    d->subProp("Topic")->setValue("/test/scan");
    mask_ = dynamic_cast<rviz_projector::ProjectionMaskDisplay*>(d);
    ASSERT_NE(mask_, nullptr);
    group_ = d->subProp("Acknowledge");
    group_->subProp("Path topic")->setValue("/test/ack_plan");
    group_->subProp("Robot frame")->setValue("test_base");
    group_->subProp("Line width")->setValue(kWidth);
    ASSERT_TRUE(waitFor([&] { return scan_pub_.getNumSubscribers() > 0; }));
    ASSERT_TRUE(waitFor([&] {
      return rviz_->manager()->getTF2BufferPtr()->canTransform("map", "test_laser", ros::Time()) &&
             rviz_->manager()->getTF2BufferPtr()->canTransform("map", "test_base", ros::Time());
    }));
  }

  void at(double t) { ros::Time::setNow(start_ + ros::Duration(t)); }

  /// Switches the group on and publishes the path along +x from the robot.
  void switchOn(const std::vector<Vec3>& path = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {3.0, 0.0, 0.0}})
  {
    group_->setValue(true);
    ASSERT_TRUE(waitFor([&] { return plan_pub_.getNumSubscribers() > 0; }));
    const std::size_t before = mask_->acknowledgeSource().pathMessages();
    plan_pub_.publish(makePath("map", path));
    ASSERT_TRUE(waitFor([&] { return mask_->acknowledgeSource().pathMessages() > before; }));
  }

  /// Publishes a scan of a person at `centre`, waits until the mask used it; returns its points.
  std::vector<Vec2> person(const Vec2& centre)
  {
    std::vector<Vec2> points;
    scan_pub_.publish(personScan(centre, ros::Time::now(), points));
    EXPECT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("17 returns masked") &&
                                     scanSeenAt(ros::Time::now()); }));
    return points;
  }

  /// A scan with no return at all (the person left).
  void nobody()
  {
    sensor_msgs::LaserScan scan;
    scan.header.frame_id = "test_laser";
    scan.header.stamp = ros::Time::now();
    scan.angle_increment = 0.01f;
    scan.range_min = 0.05f;
    scan.range_max = 10.0f;
    scan.ranges.assign(5, std::numeric_limits<float>::infinity());
    scan_pub_.publish(scan);
    EXPECT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("0 returns masked"); }));
  }

  /// Whether the tracker's latest update is from the scan stamped `stamp` (the scan was used).
  bool scanSeenAt(const ros::Time& stamp) const
  {
    for (const auto& t : mask_->acknowledgeSource().tracks())
    {
      if (t.seen && std::abs(t.last_seen - stamp.toSec()) < 1e-6)
      {
        return true;
      }
    }
    return false;
  }

  bool colourAt(const QImage& image, const Vec2& floor, QRgb colour) const
  {
    const Vec2 px = windowPixel(floor);
    const QPoint p(int(std::lround(px.x)), int(std::lround(px.y)));
    EXPECT_TRUE(image.rect().contains(p)) << "the test judges a floor point out of view: " << floor.x << ", " << floor.y;
    return image.rect().contains(p) && sameColour(image.pixel(p), colour, 30);
  }

  /// Whether the arc's middle line shows in `image` at the oracle's places: towards the robot and
  /// 40 degrees either side (the arc spans 120).
  bool arcShown(const QImage& image, const ArcOracle& arc, QRgb colour = kArc) const
  {
    for (double a : {0.0, -0.7, 0.7})
    {
      if (!colourAt(image, arc.at(a), colour))
      {
        return false;
      }
    }
    return true;
  }

  ros::Time start_;
  ros::Publisher scan_pub_, plan_pub_;
  rviz_projector::ProjectionMaskDisplay* mask_ = nullptr;
  rviz::Property* group_ = nullptr;
};
}  // namespace

TEST_F(AcknowledgeTest, ArcOnTheRobotsSideNeverOnTheFeet)
{
  switchOn();
  const std::vector<Vec2> points = person({1.1, 0.3});
  // Within one frame of the scan: its arc was uploaded in the same call as its mask (no frame
  // between them shows the mask without the arc).
  EXPECT_EQ(mask_->columns(), 17u);
  EXPECT_GT(mask_->acknowledgeTriangles(), 0u);
  const ArcOracle arc(points, {0.0, 0.0});
  const QImage frame = imagePart(grabWhen([&](const QImage& image) { return arcShown(imagePart(image), arc); }));
  EXPECT_TRUE(arcShown(frame, arc)) << "the arc at " << arc.at(0.0).x << ", " << arc.at(0.0).y;
  EXPECT_FALSE(colourAt(frame, arc.at(M_PI), kArc)) << "nothing on the far side of the person";
  EXPECT_FALSE(colourAt(frame, arc.at(1.4), kArc)) << "the arc spans 120 degrees, not 160";
  for (const Vec2& p : points)
  {
    EXPECT_TRUE(colourAt(frame, p, kBlack)) << "the person's feet stay dark at " << p.x << ", " << p.y;
  }
  // No arc pixel anywhere within the masked feet (radius + Margin around the mean, every 2 cm).
  for (double dx = -0.3; dx <= 0.3; dx += 0.02)
  {
    for (double dy = -0.3; dy <= 0.3; dy += 0.02)
    {
      if (std::hypot(dx, dy) <= arc.radius + kMargin)
      {
        EXPECT_FALSE(colourAt(frame, {arc.mean.x + dx, arc.mean.y + dy}, kArc));
      }
    }
  }
  EXPECT_EQ(mask_->acknowledgeSource().tracks().size(), 1u);
  EXPECT_TRUE(statusOf(mask_, "Acknowledge").text.startsWith("1 of 1 people acknowledged"))
      << statusOf(mask_, "Acknowledge").text.toStdString();
}

TEST_F(AcknowledgeTest, SideArrowOnThePathsSide)
{
  group_->subProp("Side arrow")->setValue(true);
  // The path runs along +x 0.7 m to the right of the person (y = -0.7): the arrow is between them.
  switchOn({{0.0, -0.7, 0.0}, {3.0, -0.7, 0.0}});
  const ArcOracle arc(person({1.3, 0.0}), {0.0, 0.0});
  // The arrow's centre line: beside the mean towards the path, 2 line widths beyond the arc's outer
  // radius, running along +x. Its middle and a point 5 cm behind it are on its shaft; the same place
  // mirrored to the person's other side has nothing.
  const double beside = arc.middle + 0.5 * kWidth + 2.0 * kWidth;
  const auto shownOn = [&](const QImage& image, double sign) {
    const Vec2 shaft{arc.mean.x, arc.mean.y + sign * beside};
    return colourAt(image, shaft, kArc) && colourAt(image, {shaft.x - 0.05, shaft.y}, kArc) &&
           colourAt(image, {shaft.x, arc.mean.y - sign * beside}, kBlack);
  };
  QImage frame = imagePart(grabWhen([&](const QImage& image) { return shownOn(imagePart(image), -1.0); }));
  EXPECT_TRUE(shownOn(frame, -1.0)) << "the path passes on the person's right";
  saveShot(frame, "acknowledge");
  // The path moved to the person's left (y = +0.7): the arrow moves with it.
  switchOn({{0.0, 0.7, 0.0}, {3.0, 0.7, 0.0}});
  frame = imagePart(grabWhen([&](const QImage& image) { return shownOn(imagePart(image), 1.0); }));
  EXPECT_TRUE(shownOn(frame, 1.0)) << "the path passes on the person's left";
}

TEST_F(AcknowledgeTest, NoneOutOfRangeOrWithTheGroupOff)
{
  switchOn();
  const ArcOracle arc(person({1.5, 0.45}), {0.0, 0.0});
  ASSERT_TRUE(arcShown(imagePart(grabWhen([&](const QImage& image) { return arcShown(imagePart(image), arc); })), arc));
  // The person's centre is about 0.43 m from the path: out of a Range of 0.3.
  group_->subProp("Range")->setValue(0.3);
  QImage frame = imagePart(grabWhen([&](const QImage& image) { return countColour(imagePart(image), kArc) == 0; }));
  EXPECT_EQ(countColour(frame, kArc), 0);
  EXPECT_TRUE(statusOf(mask_, "Acknowledge").text.startsWith("0 of 1 people acknowledged"));
  group_->subProp("Range")->setValue(1.5);
  ASSERT_TRUE(arcShown(imagePart(grabWhen([&](const QImage& image) { return arcShown(imagePart(image), arc); })), arc));
  group_->setValue(false);
  frame = imagePart(grabWhen([&](const QImage& image) { return countColour(imagePart(image), kArc) == 0; }));
  EXPECT_EQ(countColour(frame, kArc), 0);
  EXPECT_EQ(mask_->acknowledgeTriangles(), 0u);
  EXPECT_FALSE(statusOf(mask_, "Acknowledge").present);
}

TEST_F(AcknowledgeTest, FadesAndIsGoneAfterHold)
{
  group_->subProp("Hold")->setValue(1.0);
  switchOn();
  const ArcOracle arc(person({1.5, 0.45}), {0.0, 0.0});
  ASSERT_TRUE(arcShown(imagePart(grabWhen([&](const QImage& image) { return arcShown(imagePart(image), arc); })), arc));
  at(0.2);
  nobody();  // last seen at 0: fading from then on, linearly over Hold = 1 s
  at(0.5);
  const QRgb half = qRgb(128, 128, 128);  // half the colour over the black background
  QImage frame = imagePart(grabWhen([&](const QImage& image) { return arcShown(imagePart(image), arc, half); }));
  EXPECT_TRUE(arcShown(frame, arc, half)) << "half faded half a Hold after the person was last seen";
  at(0.9);
  ASSERT_TRUE(waitFor([&] { return mask_->acknowledgeTriangles() > 0; })) << "still there before Hold";
  at(1.1);
  ASSERT_TRUE(waitFor([&] { return mask_->acknowledgeTriangles() == 0; })) << "gone after Hold";
  frame = imagePart(grabWhen([&](const QImage& image) { return countColour(imagePart(image), kArc, 60) == 0; }));
  EXPECT_EQ(countColour(frame, kArc, 60), 0);
  EXPECT_TRUE(mask_->acknowledgeSource().tracks().empty());
}

TEST_F(AcknowledgeTest, AWalkingPersonKeepsOneArcThatFollows)
{
  switchOn();
  std::vector<Vec2> points;
  std::uint32_t id = 0;
  for (int k = 0; k <= 5; ++k)  // 1 m/s along +x, a scan every 0.1 s
  {
    at(0.1 * k);
    points = person({1.1 + 0.1 * k, 0.45});
    const ArcOracle arc(points, {0.0, 0.0});
    ASSERT_EQ(mask_->acknowledgeSource().tracks().size(), 1u) << "one person at scan " << k;
    const auto& track = mask_->acknowledgeSource().tracks()[0];
    if (k == 0)
    {
      id = track.id;
    }
    EXPECT_EQ(track.id, id) << "the same person at scan " << k;
    EXPECT_NEAR(track.position.x, arc.mean.x, 1e-4);
    EXPECT_NEAR(track.position.y, arc.mean.y, 1e-4);
  }
  const ArcOracle arc(points, {0.0, 0.0});
  const QImage frame = imagePart(grabWhen([&](const QImage& image) { return arcShown(imagePart(image), arc); }));
  EXPECT_TRUE(arcShown(frame, arc)) << "the arc follows to the last place";
  EXPECT_TRUE(statusOf(mask_, "Acknowledge").text.startsWith("1 of 1 people acknowledged"));
}

TEST_F(AcknowledgeTest, BadInputGivesAStatusNotACrash)
{
  group_->setValue(true);
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Acknowledge").text.contains("No path received yet"); }))
      << statusOf(mask_, "Acknowledge").text.toStdString();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  switchOn({{0.0, 0.0, 0.0}, {nan, 0.0, 0.0}, {3.0, 0.0, 0.0}});
  person({1.5, 0.45});
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Acknowledge").text.contains("NaN/Inf"); }))
      << statusOf(mask_, "Acknowledge").text.toStdString();
  EXPECT_EQ(statusOf(mask_, "Acknowledge").level, rviz::StatusProperty::Warn);
  EXPECT_GT(mask_->acknowledgeTriangles(), 0u) << "the usable poses still make a path";
  switchOn({{nan, 0.0, 0.0}});
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Acknowledge").text.contains("no usable pose"); }));
  ASSERT_TRUE(waitFor([&] { return mask_->acknowledgeTriangles() == 0; }));
  // NaN ranges, then a scan of 100,000 returns (every other beam short: many specks, one wall).
  switchOn();
  sensor_msgs::LaserScan scan;
  scan.header.frame_id = "test_laser";
  scan.header.stamp = ros::Time::now();
  scan.angle_min = -1.0f;
  scan.angle_increment = 2e-5f;
  scan.range_min = 0.05f;
  scan.range_max = 10.0f;
  scan.ranges.assign(100000, std::numeric_limits<float>::quiet_NaN());
  scan_pub_.publish(scan);
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("100000 ignored"); }));
  for (std::size_t i = 0; i < scan.ranges.size(); ++i)
  {
    scan.ranges[i] = (i / 40) % 2 ? 1.2f : 3.0f;
  }
  scan.header.stamp = ros::Time::now();
  scan_pub_.publish(scan);
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("100000 returns"); }, 20.0));
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Acknowledge").present; }));
  EXPECT_LE(mask_->acknowledgeSource().tracks().size(), rviz_projector::AcknowledgeSource::kMaxPeople);
  // The robot's frame missing from tf.
  group_->subProp("Robot frame")->setValue("no_such_frame");
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Acknowledge").text.contains("No transform from the Robot frame"); }));
  // An error; a warning while ROS time has just started (rviz's tf buffer may still be filling).
  EXPECT_NE(statusOf(mask_, "Acknowledge").level, rviz::StatusProperty::Ok);
}

namespace
{
class AcknowledgeConfigTest : public RvizTest
{
};
}  // namespace

TEST_F(AcknowledgeConfigTest, PropertiesAreSavedAndLoaded)
{
  const std::map<std::string, QVariant> values = {
      {"Path topic", "/robot/plan"}, {"Robot frame", "robot"},       {"Range", 2.25},
      {"Distance", 0.35},            {"Arc angle", 150.0},           {"Line width", 0.07},
      {"Color", QColor(10, 20, 30)}, {"Hold", 2.5},                  {"Side arrow", true},
      {"Cluster gap", 0.25},         {"Min cluster width", 0.08},    {"Max cluster width", 0.9},
      {"Min points", 4}};
  const std::map<std::string, std::string> shown =
      expectGroupSavedAndLoaded("Acknowledge", values, "rviz_projector/ProjectionMask");
  EXPECT_EQ(shown.at("Path topic"), "/robot/plan");
  EXPECT_EQ(shown.at("Min points"), "4");
}

TEST_F(AcknowledgeConfigTest, UnusableValuesAreReplacedAndReported)
{
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readString(config, R"(
Displays:
  - Class: rviz_projector/ProjectionMask
    Name: Bad acknowledge
    Enabled: true
    Topic: /test/scan
    Acknowledge:
      Value: true
      Range: -3
      Hold: .nan
      Line width: abc
      Min points: 0
)");
  ASSERT_FALSE(reader.error());
  rviz_->manager()->load(config);
  ASSERT_EQ(rviz_->manager()->getRootDisplayGroup()->numDisplays(), 1);
  rviz::Display* d = rviz_->manager()->getRootDisplayGroup()->getDisplayAt(0);
  rviz::Property* group = d->subProp("Acknowledge");
  EXPECT_TRUE(group->getValue().toBool());
  EXPECT_GE(group->subProp("Range")->getValue().toDouble(), 0.0);
  EXPECT_GE(group->subProp("Min points")->getValue().toInt(), 1);
  const Status s = statusOf(d, "Config");
  ASSERT_TRUE(s.present);
  for (const char* name : {"Range: '-3'", "Hold", "Line width: 'abc'", "Min points: '0'"})
  {
    EXPECT_NE(s.text.indexOf(name), -1) << name << " missing in: " << s.text.toStdString();
  }
}

TEST_F(AcknowledgeConfigTest, AConfigWithoutTheGroupLoadsWithItOff)
{
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readString(config, R"(
Displays:
  - Class: rviz_projector/ProjectionMask
    Name: Saved before Acknowledge existed
    Enabled: true
    Topic: /test/scan
    Height: 1.5
)");
  ASSERT_FALSE(reader.error());
  rviz_->manager()->load(config);
  ASSERT_EQ(rviz_->manager()->getRootDisplayGroup()->numDisplays(), 1);
  rviz::Display* d = rviz_->manager()->getRootDisplayGroup()->getDisplayAt(0);
  EXPECT_FALSE(d->subProp("Acknowledge")->getValue().toBool());
  EXPECT_NEAR(d->subProp("Acknowledge")->subProp("Range")->getValue().toDouble(), 1.5, 1e-6);
  EXPECT_NEAR(d->subProp("Acknowledge")->subProp("Hold")->getValue().toDouble(), 1.0, 1e-6);
  spinFor(0.2);  // statuses settle (nothing to wait for: the absence of a status is the verdict)
  EXPECT_FALSE(statusOf(d, "Acknowledge").present);
  EXPECT_FALSE(statusOf(d, "Config").present) << statusOf(d, "Config").text.toStdString();
}
