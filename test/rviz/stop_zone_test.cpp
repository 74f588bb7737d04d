// ProjectedPath's Stop zone (issue 25) in a real rviz, judged on the projector output's pixels: the
// bar's far edge where the stopping distance puts it, the fill between robot and bar, stripes when
// hatched, the speed filter's step response, the clip at the destination; statuses for no, stale and
// NaN odometry; the properties saved and loaded, and a config without the group. ROS time is
// simulated (ros::Time::setNow). Expected places come from the formula d = v^2 / (2 a) + v t and the
// documented filter (first order, tau = 0.3 s) written out here, and from image_geometry
// (windowPixel), never from the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <nav_msgs/Odometry.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/properties/property.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>
#include <tf2_ros/buffer.h>

#include "projector_test_fixture.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"

using namespace rviz_projector_test;

namespace
{
constexpr double kRobotX = 0.3;           // the robot (base_link) and the path's start
constexpr double kDecel = 0.5, kReaction = 0.3;
constexpr double kSide = 0.1;             // sample beside the arrows (heads 0.12 wide), inside the zone (0.3 wide)
const QRgb kOrange = qRgb(255, 140, 0);   // the default Color, opaque (the bar)
const QRgb kOrangeFill = qRgb(102, 56, 0);  // 0.4 of it over black (the fill, Alpha 0.4)
const QRgb kZoneBlue = qRgb(0, 128, 255);

/// The formula, by hand.
double stopDistance(double v)
{
  return v * v / (2.0 * kDecel) + v * kReaction;
}

std::vector<Vec2> straightPath(double end)
{
  return lineAlongX(kRobotX, end);
}

class StopZoneTest : public ProjectorSceneTest
{
protected:
  void SetUp() override
  {
    ProjectorSceneTest::SetUp();
    start_ = monotonicTestStart(2.0);
    ros::Time::setNow(start_);
    odom_pub_ = nh_.advertise<nav_msgs::Odometry>("/test/odom", 5);
  }

  void at(double t) { ros::Time::setNow(start_ + ros::Duration(t)); }

  /// A path from the robot (standing at x 0.3 facing +x) to x = `end`, the stop zone on with its
  /// defaults (Deceleration 0.5, Reaction time 0.3) on /test/odom.
  bool pathWithStopZone(double end)
  {
    path_ = addFloorPathFromRobot(straightPath(end), kRobotX, 0.0);
    if (path_ == nullptr)
    {
      return false;
    }
    zone()->subProp("Odometry topic")->setValue("/test/odom");
    zone()->setValue(true);
    return waitFor([&] { return odom_pub_.getNumSubscribers() > 0; });
  }

  rviz::Property* zone() { return path_->subProp("Stop zone"); }

  /// Odometry with the twist (vx, vy) in the robot's frame; returns once the display took it (its
  /// arrival time is the ROS time then: time may move on after this).
  /// Odometry of (vx, vy) stamped `stamp` (default: now), once the display took it.
  void publishOdometry(double vx, double vy = 0.0, ros::Time stamp = ros::Time::now())
  {
    const std::size_t before = path_->odometryMessages();
    nav_msgs::Odometry msg;
    msg.header.stamp = stamp;
    msg.header.frame_id = "odom";
    msg.child_frame_id = "base_link";
    msg.pose.pose.orientation.w = 1.0;
    msg.twist.twist.linear.x = vx;
    msg.twist.twist.linear.y = vy;
    odom_pub_.publish(msg);
    EXPECT_TRUE(waitFor([&] { return path_->odometryMessages() > before; })) << "odometry not taken";
  }

  QRgb colourAt(const QImage& frame, const Vec2& floor) const
  {
    const Vec2 px = windowPixel(floor);
    return frame.pixel(int(std::lround(px.x)), int(std::lround(px.y)));
  }

  QImage grabUntil(const std::function<bool(const QImage&)>& ok) { return imagePart(grabWhen(ok, 8.0)); }

  /// Walking along y = `y` from x 0.5 (1 mm steps), the last floor point whose pixel has `colour`
  /// (NaN: none).
  double lastX(const QImage& frame, QRgb colour, double y = kSide, double to = 1.7) const
  {
    double last = std::numeric_limits<double>::quiet_NaN();
    for (double x = 0.5; x <= to + 1e-9; x += 0.001)
    {
      if (sameColour(colourAt(frame, {x, y}), colour, 40))
      {
        last = x;
      }
    }
    return last;
  }

  /// Pixels between the oracle's pixels of two floor points.
  double pixelDistance(const Vec2& a, const Vec2& b) const
  {
    const Vec2 pa = windowPixel(a), pb = windowPixel(b);
    return std::hypot(pa.x - pb.x, pa.y - pb.y);
  }

  /// The frame once the bar's far edge is within 2 pixels of the stopping point `stop_x`.
  QImage barAt(double stop_x, double y = kSide)
  {
    return grabUntil([&](const QImage& image) {
      const double last = lastX(image, kOrange, y);
      return std::isfinite(last) && pixelDistance({last, y}, {stop_x, y}) <= 2.0;
    });
  }

  ros::Time start_;
  rviz_projector::ProjectedPathDisplay* path_ = nullptr;
  ros::Publisher odom_pub_;
};
}  // namespace

TEST_F(StopZoneTest, BarSitsAtTheStoppingDistanceWithTheFloorFilledBeforeIt)
{
  ASSERT_TRUE(pathWithStopZone(2.5));
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").text.contains("No odometry received yet"); }));
  // 0.8 m/s (as x 0.48, y 0.64: the planar norm): d = 0.64 + 0.24 = 0.88 m, the bar's far edge at x 1.18.
  publishOdometry(0.48, 0.64);
  const double stop_x = kRobotX + stopDistance(0.8);
  ASSERT_NEAR(stop_x, 1.18, 1e-12);
  const QImage frame = barAt(stop_x);
  saveShot(frame, "cues-stop-zone");
  const double last = lastX(frame, kOrange);
  ASSERT_TRUE(std::isfinite(last)) << "no bar drawn";
  EXPECT_LE(pixelDistance({last, kSide}, {stop_x, kSide}), 2.0) << "bar's far edge at x = " << last;
  EXPECT_TRUE(sameColour(colourAt(frame, {stop_x - 0.025, kSide}), kOrange, 30)) << "the bar, 5 cm thick";
  EXPECT_TRUE(sameColour(colourAt(frame, {stop_x - 0.025, -kSide}), kOrange, 30)) << "across the path";
  EXPECT_TRUE(sameColour(colourAt(frame, {stop_x + 0.02, kSide}), kBlack, 20)) << "nothing beyond the bar";
  for (double x : {0.6, 0.8, 1.0, 1.1})
  {
    EXPECT_TRUE(sameColour(colourAt(frame, {x, kSide}), kOrangeFill, 20))
        << "fill at x = " << x << ": " << describe(colourAt(frame, {x, kSide}));
  }
  EXPECT_TRUE(sameColour(colourAt(frame, {0.8, 0.2}), kBlack, 20)) << "0.3 m wide: nothing at y = 0.2";
  EXPECT_GT(countColour(frame, kArrowMagenta), 100) << "the arrows are still drawn";
  EXPECT_EQ(statusOf(path_, "Stop zone").level, rviz::StatusProperty::Ok);
  EXPECT_GT(path_->stopZoneTriangleCount(), 0u);

  // The filter: 0.4 m/s from t = 1; 0.3 s later (one time constant) the speed is
  // 0.4 + (0.8 - 0.4) exp(-1).
  at(1.0);
  publishOdometry(0.4);
  at(1.3);
  const double v = 0.4 + 0.4 * std::exp(-1.0);
  const double slower_x = kRobotX + stopDistance(v);
  const QImage slower = barAt(slower_x);
  EXPECT_LE(pixelDistance({lastX(slower, kOrange), kSide}, {slower_x, kSide}), 2.0)
      << "one time constant after the step: bar at x = " << slower_x << " (unfiltered: "
      << kRobotX + stopDistance(0.4) << ")";

  // Hatched: stripes 5 cm long every 15 cm from the robot (x 0.3): [0.6, 0.65] lit, 0.7 dark.
  at(1.4);
  publishOdometry(0.8);
  at(5.0);
  publishOdometry(0.8);  // settled at 0.8 again: bar at 1.18
  zone()->subProp("Style")->setValue("Hatched");
  const QImage hatched = grabUntil([&](const QImage& image) {
    return sameColour(colourAt(image, {0.7, kSide}), kBlack, 20) && sameColour(colourAt(image, {0.625, kSide}), kOrangeFill, 20);
  });
  EXPECT_TRUE(sameColour(colourAt(hatched, {0.625, kSide}), kOrangeFill, 20)) << "a stripe";
  EXPECT_TRUE(sameColour(colourAt(hatched, {0.7, kSide}), kBlack, 20)) << "between stripes";
  EXPECT_TRUE(sameColour(colourAt(hatched, {0.925, kSide}), kOrangeFill, 20)) << "a stripe";
  EXPECT_LE(pixelDistance({lastX(hatched, kOrange), kSide}, {stop_x, kSide}), 2.0);
  saveShot(hatched, "cues-stop-zone-hatched");

  // Colour and width: a blue zone 0.5 m wide reaches y = 0.2.
  zone()->subProp("Style")->setValue("Filled");
  zone()->subProp("Color")->setValue(QColor(0, 128, 255));
  zone()->subProp("Alpha")->setValue(1.0);
  zone()->subProp("Width")->setValue(0.5);
  const QImage blue = grabUntil([&](const QImage& image) { return sameColour(colourAt(image, {0.8, 0.2}), kZoneBlue, 30); });
  EXPECT_TRUE(sameColour(colourAt(blue, {0.8, 0.2}), kZoneBlue, 30));
  EXPECT_TRUE(sameColour(colourAt(blue, {0.8, 0.3}), kBlack, 20));
}

TEST_F(StopZoneTest, FiltersOnTheOdometrysStampsNotTheirArrival)
{
  // As a robot's odometry arrives: measured 0.2 s before it reaches rviz. Standing (0 m/s) from
  // t = 1, then 1.2 m/s measured at t = 2.0, arriving at 2.2. On the stamps, at 2.2 the filter has
  // had 0.2 s of the new speed: 1.2 (1 - exp(-0.2 / 0.3)). On the arrival it would still be 0.
  at(1.0);
  ASSERT_TRUE(pathWithStopZone(2.5));
  publishOdometry(0.0);
  at(2.2);
  publishOdometry(1.2, 0.0, start_ + ros::Duration(2.0));
  const double v = 1.2 * (1.0 - std::exp(-0.2 / 0.3));
  const double stop_x = kRobotX + stopDistance(v);
  const QImage frame = barAt(stop_x);
  EXPECT_LE(pixelDistance({lastX(frame, kOrange), kSide}, {stop_x, kSide}), 2.0)
      << "v = " << v << " m/s on the stamps: bar at x = " << stop_x;
  // A stamp the clock makes implausible (an hour ahead: an unsynchronised clock) counts from its
  // arrival instead: at 2.6, 0.4 m/s "measured" then; 0.3 s later (one time constant) the speed
  // is 0.4 + (v(2.6) - 0.4) exp(-1), where v(2.6) is the first step's filter 0.6 s on.
  at(2.6);
  publishOdometry(0.4, 0.0, start_ + ros::Duration(3600.0));
  at(2.9);
  const double v26 = 1.2 * (1.0 - std::exp(-0.6 / 0.3));
  const double v29 = 0.4 + (v26 - 0.4) * std::exp(-1.0);
  const double later_x = kRobotX + stopDistance(v29);
  const QImage later = barAt(later_x);
  EXPECT_LE(pixelDistance({lastX(later, kOrange), kSide}, {later_x, kSide}), 2.0)
      << "v = " << v29 << " m/s from the arrival: bar at x = " << later_x;
}

TEST_F(StopZoneTest, AResetKeepsTheOdometryOfTheCurrentTimeLineAndAJumpBackForgetsIt)
{
  at(2.0);
  ASSERT_TRUE(pathWithStopZone(2.5));
  publishOdometry(0.8);
  const double stop_x = kRobotX + stopDistance(0.8);
  barAt(stop_x);
  // rviz's Reset (rviz also resets at every backward jump of ROS time, at a moment of its own, after
  // some of the new pass's odometry may have arrived): odometry measured at or before the clock's
  // time stays, so the latched path comes back with the zone, without a new odometry message.
  const std::size_t messages = path_->odometryMessages();
  path_->reset();
  const QImage after = barAt(stop_x);
  EXPECT_LE(pixelDistance({lastX(after, kOrange), kSide}, {stop_x, kSide}), 2.0) << "the zone after Reset";
  EXPECT_EQ(path_->odometryMessages(), messages) << "no new odometry was needed";
  EXPECT_FALSE(statusOf(path_, "Stop zone").text.contains("No odometry")) << statusOf(path_, "Stop zone").text.toStdString();
  // ROS time jumping back (a bag loop) forgets what was measured after the new time.
  at(1.0);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").text.contains("No odometry received yet"); }))
      << statusOf(path_, "Stop zone").text.toStdString();
  publishOdometry(0.4);  // the new time line's first measurement, taken as it is
  const double slower_x = kRobotX + stopDistance(0.4);
  const QImage slower = barAt(slower_x);
  EXPECT_LE(pixelDistance({lastX(slower, kOrange), kSide}, {slower_x, kSide}), 2.0) << "the new pass's speed alone";
}

TEST_F(StopZoneTest, NeverBeyondTheDestination)
{
  ASSERT_TRUE(pathWithStopZone(1.5));  // destination circle (0.2 m) at x 1.5, in view
  publishOdometry(2.0);                // d = 4 + 0.6 = 4.6 m: far beyond the path's 1.2 m
  const double y = 0.12;               // beside the destination circle
  const QImage frame = barAt(1.5, y);
  EXPECT_LE(pixelDistance({lastX(frame, kOrange, y), y}, {1.5, y}), 2.0) << "the bar ends at the destination";
  EXPECT_TRUE(sameColour(colourAt(frame, {1.53, y}), kBlack, 20)) << "nothing beyond the destination";
}

TEST_F(StopZoneTest, StartsWhereTheRobotIsOnThePath)
{
  ASSERT_TRUE(pathWithStopZone(2.5));
  publishStaticTransform("map", "base_link", 0.6, 0.05, 0.0, 0.0);  // beside the path at x 0.6
  // The odometry below redraws the zone: only once tf has the robot's new place (no frame of a
  // projector that is not on the robot redraws it on a tf change alone).
  ASSERT_TRUE(waitFor([&] {
    try
    {
      return std::abs(rviz_->manager()->getTF2BufferPtr()->lookupTransform("map", "base_link", ros::Time())
                          .transform.translation.x - 0.6) < 1e-9;
    }
    catch (const std::exception&)
    {
      return false;
    }
  }));
  publishOdometry(0.8);
  // ROS time stands still in this test, and the display redraws once per new ROS time (or on news):
  // the odometry's redraw can still have read rviz's tf cache of the frame before. A moment later
  // (the speed unchanged: the first reading is taken as it is) the robot's new place is drawn.
  at(0.05);
  const double stop_x = 0.6 + stopDistance(0.8);  // 1.48
  const QImage frame = barAt(stop_x);
  EXPECT_LE(pixelDistance({lastX(frame, kOrange), kSide}, {stop_x, kSide}), 2.0);
  EXPECT_TRUE(sameColour(colourAt(frame, {0.55, kSide}), kBlack, 20)) << "behind the robot: nothing";
  EXPECT_TRUE(sameColour(colourAt(frame, {0.65, kSide}), kOrangeFill, 20)) << "ahead of the robot: the fill";
}

TEST_F(StopZoneTest, ArrowsAreDrawnOverTheZoneAlsoWhenTheyFade)
{
  // A fading horizon makes the arrows translucent: OGRE would sort them and the zone by their
  // distance from the projector (the arrows' middle lies further away), drawing the bar over them.
  ASSERT_TRUE(pathWithStopZone(2.5));
  path_->subProp("Horizon")->subProp("Length")->setValue(2.0);
  path_->subProp("Horizon")->subProp("Fade")->setValue(1.0);
  path_->subProp("Horizon")->setValue(true);
  // The bar's far edge at x 1.30 (d = 1.0 m: v^2 + 0.3 v = 1), the bar on [1.25, 1.30]: across the
  // head of the arrow whose tip is at 1.35 (tips every 0.25 m from 2.35 back; heads 0.08 long).
  const double v = (-0.3 + std::sqrt(0.09 + 4.0)) / 2.0;
  publishOdometry(v);
  const double stop_x = kRobotX + stopDistance(v);
  ASSERT_NEAR(stop_x, 1.30, 1e-9);
  const QImage frame = barAt(stop_x);
  saveShot(frame, "cues-stop-zone-under-arrows");
  EXPECT_TRUE(sameColour(colourAt(frame, {1.29, 0.0}), kArrowMagenta, 40))
      << "arrow head over the bar: " << describe(colourAt(frame, {1.29, 0.0}));
  EXPECT_TRUE(sameColour(colourAt(frame, {1.275, 0.04}), kArrowMagenta, 40))
      << "arrow head over the bar, off centre: " << describe(colourAt(frame, {1.275, 0.04}));
  EXPECT_TRUE(sameColour(colourAt(frame, {1.275, 0.1}), kOrange, 30)) << "the bar beside the head";
}

namespace
{
/// Speed-coded spacing by hand: tips measured back from the destination, the first 0.15 m from it
/// (circle radius 0.1 + gap 0.05), each next one max(min, min(v, sqrt(2 a d)) T) further; an arrow
/// `arrow` long must fit on the path (`length`).
std::vector<double> codedTips(double v, double a, double t, double min, double arrow, double length)
{
  std::vector<double> tips;
  for (double d = 0.15; d + arrow <= length + 1e-9; d += std::max(min, std::min(v, std::sqrt(2.0 * a * d)) * t))
  {
    tips.push_back(d);
  }
  return tips;
}
}  // namespace

TEST_F(StopZoneTest, SpeedCodedSpacingCrowdsTheArrowsWhereTheRobotBrakes)
{
  ASSERT_TRUE(pathWithStopZone(1.5));  // path length 1.2, destination at x 1.5 (in view)
  path_->subProp("Shaft length")->setValue(0.03);  // arrows 0.07 m long: apart even at Min spacing
  path_->subProp("Head length")->setValue(0.04);
  zone()->subProp("Alpha")->setValue(0.0);  // no fill under the arrows (the opaque bar lies under them)
  zone()->subProp("Deceleration")->setValue(0.1);
  rviz::Property* coded = zone()->subProp("Speed-coded spacing");
  coded->subProp("Time step")->setValue(0.5);
  coded->subProp("Min spacing")->setValue(0.1);
  coded->setValue(true);
  // Tips on the centre line: the ends (largest x) of the magenta runs along y = 0.
  const auto tipsIn = [&](const QImage& image) {
    std::vector<double> tips;
    bool inside = false;
    for (double x = 0.5; x <= 1.45; x += 0.001)
    {
      const bool magenta = sameColour(colourAt(image, {x, 0.0}), kArrowMagenta, 60);
      if (inside && !magenta)
      {
        tips.push_back(1.5 - (x - 0.001));  // back from the destination
      }
      inside = magenta;
    }
    std::reverse(tips.begin(), tips.end());
    return tips;
  };
  const auto matches = [&](const QImage& image, std::vector<double> expected) {
    // Judged where the whole arrow is surely lit: tips up to 0.9 m back from the destination
    // (x >= 0.6; the lit area begins near x 0.45).
    expected.erase(std::remove_if(expected.begin(), expected.end(), [](double d) { return d > 0.9; }), expected.end());
    std::vector<double> tips = tipsIn(image);
    tips.erase(std::remove_if(tips.begin(), tips.end(), [](double d) { return d > 0.9; }), tips.end());
    if (tips.size() != expected.size())
    {
      return false;
    }
    for (std::size_t k = 0; k < tips.size(); ++k)
    {
      if (pixelDistance({1.5 - tips[k], 0.0}, {1.5 - expected[k], 0.0}) > 2.5)
      {
        return false;
      }
    }
    return true;
  };
  const auto describeTips = [&](const QImage& image) {
    std::string out;
    for (double d : tipsIn(image))
    {
      out += std::to_string(d) + " ";
    }
    return out;
  };
  // Standing (0 m/s): Min spacing everywhere.
  publishOdometry(0.0);
  const std::vector<double> standing = codedTips(0.0, 0.1, 0.5, 0.1, 0.07, 1.2);
  ASSERT_EQ(standing.size(), 10u);  // 0.15, 0.25, ... 1.05 (0.07 long: the last tip at most 1.13)
  const QImage still = grabUntil([&](const QImage& image) { return matches(image, standing); });
  EXPECT_TRUE(matches(still, standing)) << "standing, tips back from the destination: " << describeTips(still);

  // Driving at 0.4 m/s (settled: 5 time constants of the filter and more): braking from 0.4 m/s
  // at 0.1 m/s^2 starts 0.8 m before the destination; the arrows crowd on that last stretch.
  publishOdometry(0.4);
  at(3.0);
  publishOdometry(0.4);
  const std::vector<double> driving = codedTips(0.4, 0.1, 0.5, 0.1, 0.07, 1.2);
  ASSERT_EQ(driving.size(), 7u);  // 0.15, 0.25, 0.362, 0.496, 0.654, 0.835, 1.035
  const QImage moving = grabUntil([&](const QImage& image) { return matches(image, driving); });
  EXPECT_TRUE(matches(moving, driving)) << "0.4 m/s: " << describeTips(moving);
  saveShot(moving, "cues-speed-coded");

  // Off again: the constant Spacing (0.25 by default) back.
  coded->setValue(false);
  std::vector<double> constant;
  for (double d = 0.15; d + 0.07 <= 1.2 + 1e-9; d += 0.25)
  {
    constant.push_back(d);
  }
  const QImage off = grabUntil([&](const QImage& image) { return matches(image, constant); });
  EXPECT_TRUE(matches(off, constant)) << "off: " << describeTips(off);
}

TEST_F(StopZoneTest, HiddenWhileStandingAndOnStaleOrBadOdometry)
{
  ASSERT_TRUE(pathWithStopZone(2.5));
  const auto noZone = [&](const QImage& image) {
    return countColour(image, kOrange, 40) == 0 && countColour(image, kOrangeFill, 20) == 0;
  };
  const auto zoneShown = [&](const QImage& image) { return countColour(image, kOrange, 40) > 100; };
  publishOdometry(0.0);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").level == rviz::StatusProperty::Ok; }));
  EXPECT_TRUE(noZone(grabUntil(noZone))) << "standing: no zone";
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100);

  publishOdometry(0.8);  // from standing: the filter rises from 0
  at(1.0);
  publishOdometry(0.8);
  EXPECT_TRUE(zoneShown(grabUntil(zoneShown)));
  // No odometry for 2 s: stale.
  at(3.0);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").text.contains("for more than 1 s"); }));
  EXPECT_EQ(statusOf(path_, "Stop zone").level, rviz::StatusProperty::Warn);
  EXPECT_TRUE(noZone(grabUntil(noZone))) << "stale odometry: no zone";

  publishOdometry(0.8);
  EXPECT_TRUE(zoneShown(grabUntil(zoneShown))) << "fresh odometry: back";
  publishOdometry(std::numeric_limits<double>::quiet_NaN(), 0.0);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").text.contains("NaN/Inf"); }));
  EXPECT_EQ(statusOf(path_, "Stop zone").level, rviz::StatusProperty::Error);
  const QImage nan = grabUntil(noZone);
  EXPECT_TRUE(noZone(nan)) << "NaN twist: no zone";
  EXPECT_GT(countColour(nan, kArrowMagenta), 100) << "the arrows keep running";
  publishOdometry(0.0, std::numeric_limits<double>::infinity());
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").text.contains("NaN/Inf"); }));
  publishOdometry(0.8);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").level == rviz::StatusProperty::Ok; }));
  EXPECT_TRUE(zoneShown(grabUntil(zoneShown))) << "usable odometry again: back";

  // Off: no zone, no status.
  zone()->setValue(false);
  EXPECT_TRUE(noZone(grabUntil(noZone)));
  EXPECT_TRUE(waitFor([&] { return !statusOf(path_, "Stop zone").present; }));
  zone()->subProp("Odometry topic")->setValue("");
  zone()->setValue(true);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").text.contains("No Odometry topic"); }));
  zone()->subProp("Odometry topic")->setValue("not a valid topic!");
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Stop zone").level == rviz::StatusProperty::Error; }));
}

namespace
{
class StopZoneConfigTest : public RvizTest
{
protected:
  /// The first ProjectedPath of `rviz` after loading the YAML text `yaml`.
  rviz::Display* loadYaml(RvizInstance& rviz, const char* yaml)
  {
    rviz::Config config;
    rviz::YamlConfigReader reader;
    reader.readString(config, yaml);
    EXPECT_FALSE(reader.error()) << reader.errorMessage().toStdString();
    rviz.manager()->load(config);
    rviz::DisplayGroup* root = rviz.manager()->getRootDisplayGroup();
    return root->numDisplays() > 0 ? root->getDisplayAt(0) : nullptr;
  }
};
}  // namespace

TEST_F(StopZoneConfigTest, PropertiesAreSavedAndLoaded)
{
  const std::map<std::string, QVariant> values = {
      {"Odometry topic", "/robot/odom"}, {"Deceleration", 1.25}, {"Reaction time", 0.45}, {"Style", "Hatched"},
      {"Color", QColor(10, 20, 30)},     {"Alpha", 0.7},         {"Width", 0.55},
      {"Speed-coded spacing", true},     {"Speed-coded spacing/Time step", 0.8},
      {"Speed-coded spacing/Min spacing", 0.15}};
  std::map<std::string, std::string> shown = expectGroupSavedAndLoaded("Stop zone", values);
  EXPECT_EQ(shown["Style"], "Hatched");
  EXPECT_EQ(shown["Odometry topic"], "/robot/odom");
}

TEST_F(StopZoneConfigTest, AConfigWithoutTheGroupLoadsWithItOff)
{
  rviz::Display* d = loadYaml(*rviz_, R"(
Displays:
  - Class: rviz_projector/ProjectedPath
    Name: Saved before the stop zone existed
    Enabled: true
    Topic: /test/plan
    Horizon:
      Value: true
      Length: 2
)");
  ASSERT_NE(d, nullptr);
  EXPECT_FALSE(d->subProp("Stop zone")->getValue().toBool());
  EXPECT_NEAR(d->subProp("Stop zone")->subProp("Deceleration")->getValue().toDouble(), 0.5, 1e-6);
  EXPECT_NEAR(d->subProp("Stop zone")->subProp("Reaction time")->getValue().toDouble(), 0.3, 1e-6);
  EXPECT_EQ(d->subProp("Stop zone")->subProp("Style")->getValue().toString().toStdString(), "Filled");
  EXPECT_FALSE(d->subProp("Stop zone")->subProp("Speed-coded spacing")->getValue().toBool());
  spinFor(0.2);  // statuses settle (nothing to wait for: the absence of a status is the verdict)
  EXPECT_FALSE(statusOf(d, "Stop zone").present);
  EXPECT_FALSE(statusOf(d, "Config").present) << statusOf(d, "Config").text.toStdString();
}

TEST_F(StopZoneConfigTest, UnusableValuesAreReplacedAndReported)
{
  rviz::Display* d = loadYaml(*rviz_, R"(
Displays:
  - Class: rviz_projector/ProjectedPath
    Name: Bad stop zone
    Enabled: true
    Topic: /test/plan
    Stop zone:
      Value: true
      Deceleration: -2
      Reaction time: .nan
      Width: abc
      Style: Zigzag
      Speed-coded spacing:
        Value: true
        Time step: -1
        Min spacing: .inf
)");
  ASSERT_NE(d, nullptr);
  rviz::Property* zone = d->subProp("Stop zone");
  EXPECT_TRUE(zone->getValue().toBool());
  EXPECT_GT(zone->subProp("Deceleration")->getValue().toDouble(), 0.0);
  EXPECT_EQ(zone->subProp("Style")->getValue().toString().toStdString(), "Filled");
  const Status s = statusOf(d, "Config");
  ASSERT_TRUE(s.present);
  EXPECT_GT(zone->subProp("Speed-coded spacing")->subProp("Time step")->getValue().toDouble(), 0.0);
  for (const char* name : {"Deceleration: '-2'", "Reaction time", "Width: 'abc'", "Style: 'Zigzag' -> Filled",
                           "Time step: '-1'", "Min spacing"})
  {
    EXPECT_NE(s.text.indexOf(name), -1) << name << " missing in: " << s.text.toStdString();
  }
}
