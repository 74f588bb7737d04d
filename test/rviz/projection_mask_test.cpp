// ProjectionMask (issue 15) in a real rviz, judged on pixels: arrows are dark exactly where a scan
// return's column blocks the projector's beam (the test intersects each ray with the column itself,
// from the raw geometry and image_geometry's pixels - never with the code under test), the main view
// shows nothing of the mask unless asked, stale and old scans release the mask with a status, invalid
// returns are ignored, and Max lit height clips the projector view. ROS time is simulated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <vector>

#include <rviz/display.h>
#include <rviz/properties/property.h>
#include <sensor_msgs/LaserScan.h>

#include "projector_test_fixture.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projection_mask_display.h"
#include "rviz_projector/displays/projector_camera_display.h"

using namespace rviz_projector_test;

namespace
{
/// With RP_TEST_SHOTS set (a folder), saves `image` there as NAME.png: the README's pictures of the
/// cues come from these scenes.
void saveShot(const QImage& image, const char* name)
{
  if (const char* folder = std::getenv("RP_TEST_SHOTS"))
  {
    image.save(QString("%1/%2.png").arg(folder, name));
  }
}

constexpr double kTip0 = 2.35, kSpacing = 0.25;  // tips of the arrows of the path 0.3 -> 2.5 (no phase)

/// Does the segment from `a` to `b` pass through the box [lo, hi]? (slab test)
bool crossesBox(const Vec3& a, const Vec3& b, const Vec3& lo, const Vec3& hi)
{
  double t0 = 0.0, t1 = 1.0;
  const double from[3] = {a.x, a.y, a.z}, to[3] = {b.x, b.y, b.z}, low[3] = {lo.x, lo.y, lo.z},
               high[3] = {hi.x, hi.y, hi.z};
  for (int i = 0; i < 3; ++i)
  {
    const double d = to[i] - from[i];
    if (std::abs(d) < 1e-12)
    {
      if (from[i] < low[i] || from[i] > high[i])
      {
        return false;
      }
      continue;
    }
    double ta = (low[i] - from[i]) / d, tb = (high[i] - from[i]) / d;
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1)
    {
      return false;
    }
  }
  return true;
}

class ProjectionMaskTest : public ProjectorSceneTest
{
protected:
  void SetUp() override
  {
    ProjectorSceneTest::SetUp();
    start_ = ros::Time(std::floor(ros::WallTime::now().toSec()));
    ros::Time::setNow(start_);
    publishStaticTransform("map", "test_laser", 0.0, 0.0, 0.3, 0.0);
    scan_pub_ = nh_.advertise<sensor_msgs::LaserScan>("/test/scan", 5);
    rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectionMask", "Projection mask");
    d->subProp("Topic")->setValue("/test/scan");
    mask_ = dynamic_cast<rviz_projector::ProjectionMaskDisplay*>(d);
    ASSERT_NE(mask_, nullptr);
    ASSERT_TRUE(waitFor([&] { return scan_pub_.getNumSubscribers() > 0; }));
  }

  void at(double t) { ros::Time::setNow(start_ + ros::Duration(t)); }

  /// A scan from test_laser: beams at 0, 0.01, 0.02... rad with these ranges, stamped now.
  void publishScan(const std::vector<float>& ranges, const ros::Time& stamp = ros::Time::now())
  {
    sensor_msgs::LaserScan scan;
    scan.header.frame_id = "test_laser";
    scan.header.stamp = stamp;
    scan.angle_min = 0.0f;
    scan.angle_increment = 0.01f;
    scan.angle_max = 0.01f * static_cast<float>(ranges.size() - 1);
    scan.range_min = 0.05f;
    scan.range_max = 10.0f;
    scan.ranges = ranges;
    scan_pub_.publish(scan);
  }

  QRgb colourAt(const QImage& frame, const Vec2& floor) const
  {
    const Vec2 px = windowPixel(floor);
    return frame.pixel(int(std::lround(px.x)), int(std::lround(px.y)));
  }

  /// Floor points on the arrows' shafts (1 cm inside each end) of the path 0.3 -> 2.5, in view.
  std::vector<Vec2> shaftPoints() const
  {
    std::vector<Vec2> points;
    for (double tip = kTip0; tip - 0.18 >= 0.3; tip -= kSpacing)
    {
      for (double x = tip - 0.17; x <= tip - 0.09; x += 0.01)
      {
        const Vec2 px = windowPixel({x, 0.0});
        if (px.x > 2 && px.y > 2 && px.x < 1277 && px.y < 797)
        {
          points.push_back({x, 0.0});
        }
      }
    }
    return points;
  }

  ros::Time start_;
  ros::Publisher scan_pub_;
  rviz_projector::ProjectionMaskDisplay* mask_ = nullptr;
};
}  // namespace

TEST_F(ProjectionMaskTest, ArrowsAreCutExactlyWhereTheColumnBlocksTheBeam)
{
  ASSERT_NE(addPath("/test/plan", {{0.3, 0.0}, {1.0, 0.0}, {2.5, 0.0}}), nullptr);
  grabWithArrows();
  publishScan({1.2f});  // one return straight ahead of the laser: at (1.2, 0) on the floor
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 1; }));
  // The column: 0.1 m margin around (1.2, 0), floor to 2 m. A floor point is dark when the ray from
  // the projector's optical centre to it passes through the column.
  const Vec3 eye = kDemoMount.position;
  const auto occluded = [&](const Vec2& p, double grow) {
    return crossesBox(eye, Vec3{p.x, p.y, 0.0}, Vec3{1.1 - grow, -0.1 - grow, 0.0}, Vec3{1.3 + grow, 0.1 + grow, 2.0 + grow});
  };
  const QImage frame = imagePart(grabWhen([&](const QImage& image) {
    return !sameColour(colourAt(image, {1.2, 0.0}), kArrowMagenta, 30) &&
           sameColour(colourAt(image, {0.6 - 0.13, 0.0}), kArrowMagenta, 30);
  }));
  saveShot(frame, "mask-gap");
  int dark = 0, lit = 0;
  for (const Vec2& p : shaftPoints())
  {
    if (occluded(p, 0.01) != occluded(p, -0.01))
    {
      continue;  // within 1 cm of the column's outline: a pixel either way
    }
    if (occluded(p, 0.0))
    {
      EXPECT_TRUE(sameColour(colourAt(frame, p), kBlack, 30)) << "shaft point x = " << p.x << " should be masked";
      ++dark;
    }
    else
    {
      EXPECT_TRUE(sameColour(colourAt(frame, p), kArrowMagenta, 30)) << "shaft point x = " << p.x << " should be lit";
      ++lit;
    }
  }
  EXPECT_GE(dark, 20) << "the column hides part of the path";
  EXPECT_GE(lit, 20);
  EXPECT_TRUE(statusOf(mask_, "Scan").text.contains("1 returns masked"));
  // The projector's Visibility ticks the mask by default (a new projector would too).
  EXPECT_TRUE(projector_->subProp("Visibility")->subProp("Projection mask")->getValue().toBool());
}

TEST_F(ProjectionMaskTest, MainViewShowsNothingOfTheMaskUnlessAsked)
{
  rviz_->setTopDownView(1.2, 0.0, 200.0);
  const QImage before = rviz_->renderMainView();
  publishScan({1.2f});
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 1; }));
  spinFor(0.1);  // rviz renders its main view meanwhile (a span, not a condition)
  const QImage masked = rviz_->renderMainView();
  const QPoint c = rviz_->topDownPixel(1.2, 0.0);
  EXPECT_EQ(masked.pixel(c), before.pixel(c)) << "the main view draws no occluder";
  EXPECT_EQ(countColour(masked, kBlack, 10), countColour(before, kBlack, 10));
  // The projector does draw it (black over the floor point right under the column).
  mask_->subProp("Show in main view")->setValue(true);
  const QImage outlined = rviz_->renderMainView();
  EXPECT_NE(outlined.pixel(c), before.pixel(c)) << "Show in main view draws the translucent outline";
  mask_->subProp("Show in main view")->setValue(false);
  EXPECT_EQ(rviz_->renderMainView().pixel(c), before.pixel(c));
}

TEST_F(ProjectionMaskTest, StaleScanReleasesTheMaskAndOldScansAreDropped)
{
  ASSERT_NE(addPath("/test/plan", {{0.3, 0.0}, {2.5, 0.0}}), nullptr);
  grabWithArrows();
  const Vec2 behind{1.6 - 0.13, 0.0};  // a shaft point in the column's shadow
  publishScan({1.2f});
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 1; }));
  at(0.3);
  QImage frame = imagePart(grabWhen([&](const QImage& image) { return sameColour(colourAt(image, behind), kBlack, 30); }));
  EXPECT_TRUE(sameColour(colourAt(frame, behind), kBlack, 30));
  at(0.7);  // older than Max scan age 0.5 s
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 0; }));
  EXPECT_TRUE(statusOf(mask_, "Scan").text.contains("released"));
  EXPECT_EQ(statusOf(mask_, "Scan").level, rviz::StatusProperty::Warn);
  frame = imagePart(grabWhen([&](const QImage& image) { return sameColour(colourAt(image, behind), kArrowMagenta, 30); }));
  EXPECT_TRUE(sameColour(colourAt(frame, behind), kArrowMagenta, 30)) << "released: the arrow is lit again";
  // A scan stamped 1 s ago is dropped at once.
  publishScan({1.2f}, ros::Time::now() - ros::Duration(1.0));
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("dropped"); }));
  EXPECT_EQ(mask_->columns(), 0u);
}

TEST_F(ProjectionMaskTest, InvalidReturnsAreIgnoredAndCounted)
{
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  publishScan({nan, 1.2f, inf, 0.01f, 11.0f, 1.5f});
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 2; }));
  EXPECT_TRUE(statusOf(mask_, "Scan").text.contains("2 returns masked; 4 ignored"));
  publishScan({});
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 0; }));
  mask_->subProp("Margin")->setValue(-1.0);  // clamped to 0: nothing to draw, nothing breaks
  publishScan({1.2f});
  spinFor(0.1);
  EXPECT_EQ(mask_->columns(), 0u);
}

TEST_F(ProjectionMaskTest, MaxLitHeightClipsTheProjectorViewOnly)
{
  // Arrows lifted 0.8 m above the floor (the projector is at 1.2 m).
  rviz_projector::ProjectedPathDisplay* lifted = addPath("/test/plan", {{0.3, 0.0}, {2.5, 0.0}});
  ASSERT_NE(lifted, nullptr);
  lifted->subProp("Height above floor")->setValue(0.8);
  const auto magenta = [](const QImage& image) { return countColour(image, kArrowMagenta); };
  EXPECT_GT(magenta(imagePart(grabWhen([&](const QImage& i) { return magenta(i) > 200; }))), 200);
  projector_->subProp("Max lit height")->setValue(0.5);
  EXPECT_EQ(magenta(imagePart(grabWhen([&](const QImage& i) { return magenta(i) == 0; }))), 0)
      << "nothing above 0.5 m is drawn";
  EXPECT_EQ(statusOf(projector_, "Max lit height").level, rviz::StatusProperty::Ok);
  projector_->subProp("Max lit height")->setValue(1.0);  // above the lifted arrows: they are back
  EXPECT_GT(magenta(imagePart(grabWhen([&](const QImage& i) { return magenta(i) > 200; }))), 200);
  projector_->subProp("Max lit height")->setValue(1.5);  // above the projector: cannot clip, says so
  EXPECT_TRUE(waitFor([&] { return statusOf(projector_, "Max lit height").level == rviz::StatusProperty::Warn; }));
  projector_->subProp("Max lit height")->setValue(0.0);
  EXPECT_TRUE(waitFor([&] { return !statusOf(projector_, "Max lit height").present; }));
}
