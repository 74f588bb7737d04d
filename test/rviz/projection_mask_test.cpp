// ProjectionMask (issue 15) in a real rviz, judged on pixels: arrows are dark exactly where a scan
// return's column blocks the projector's beam (the test intersects each ray with the column itself,
// from the raw geometry and image_geometry's pixels - never with the code under test), the main view
// shows nothing of the mask unless asked, stale and old scans release the mask with a status, invalid
// returns are ignored, a scan is placed by the tf at its own stamp, a point cloud masks by cells (and
// waits for its tf), and Max lit height clips the projector view. ROS time is simulated.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <rviz/display.h>
#include <rviz/properties/property.h>
#include <rviz/visualization_manager.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2_ros/buffer.h>

#include "projector_test_fixture.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projection_mask_display.h"
#include "rviz_projector/displays/projector_camera_display.h"

using namespace rviz_projector_test;

namespace
{
/// With RP_TEST_SHOTS set (a folder), saves `image` there as NAME.png: the README's pictures of the
/// cues come from these scenes.
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

/// An occluder as the issue defines it: axis-aligned, floor to `height`, half-width `half` around `centre`.
struct Column
{
  Vec2 centre;
  double half = 0.1;
  double height = 2.0;
};

/// Does the ray from the projector's optical centre to the floor point `p` pass through one of the
/// columns, each grown by `grow` (m) sideways and upwards?
bool occluded(const std::vector<Column>& columns, const Vec2& p, double grow)
{
  const Vec3 eye = kDemoMount.position;
  for (const Column& c : columns)
  {
    const double w = c.half + grow;
    if (crossesBox(eye, Vec3{p.x, p.y, 0.0}, Vec3{c.centre.x - w, c.centre.y - w, 0.0},
                   Vec3{c.centre.x + w, c.centre.y + w, c.height + grow}))
    {
      return true;
    }
  }
  return false;
}

class ProjectionMaskTest : public ProjectorSceneTest
{
protected:
  void SetUp() override
  {
    ProjectorSceneTest::SetUp();
    start_ = rviz_projector_test::monotonicTestStart();  // (a flake in CI: see its comment)
    ros::Time::setNow(start_);
    publishStaticTransform("map", "test_laser", 0.0, 0.0, 0.3, 0.0);
    scan_pub_ = nh_.advertise<sensor_msgs::LaserScan>("/test/scan", 5);
    rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectionMask", "Projection mask");
    d->subProp("Topic")->setValue("/test/scan");
    mask_ = dynamic_cast<rviz_projector::ProjectionMaskDisplay*>(d);
    ASSERT_NE(mask_, nullptr);
    ASSERT_TRUE(waitFor([&] { return scan_pub_.getNumSubscribers() > 0; }));
    // The laser's static tf in rviz's buffer before the first scan (a scan may be published at once).
    ASSERT_TRUE(waitFor([&] { return rviz_->manager()->getTF2BufferPtr()->canTransform("map", "test_laser", ros::Time()); }));
  }

  void at(double t) { ros::Time::setNow(start_ + ros::Duration(t)); }

  /// A scan from `frame`: beams at 0, 0.01, 0.02... rad with these ranges, stamped now.
  void publishScan(const std::vector<float>& ranges, const ros::Time& stamp = ros::Time::now(),
                   const std::string& frame = "test_laser")
  {
    sensor_msgs::LaserScan scan;
    scan.header.frame_id = frame;
    scan.header.stamp = stamp;
    scan.angle_min = 0.0f;
    scan.angle_increment = 0.01f;
    scan.angle_max = ranges.empty() ? 0.0f : 0.01f * static_cast<float>(ranges.size() - 1);
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

  /// The path 0.3 -> 2.5 (or through `via`) drawn right on the floor (Height above floor 0, not the
  /// default 1 cm lift): the floor points the oracle judges are then the drawn points.
  bool addFloorPath(const std::vector<Vec2>& points = {{0.3, 0.0}, {2.5, 0.0}})
  {
    rviz_projector::ProjectedPathDisplay* path = addPath("/test/plan", points);
    if (path)
    {
      path->subProp("Height above floor")->setValue(0.0);
    }
    return path != nullptr;
  }

  /// Floor points on the arrows' shafts (tip - 0.18 .. tip - 0.08; 1 cm inside each end, every
  /// centimetre) of the path 0.3 -> 2.5, in view.
  std::vector<Vec2> shaftPoints() const
  {
    std::vector<Vec2> points;
    for (double tip = kTip0; tip - 0.18 >= 0.3; tip -= kSpacing)
    {
      for (int i = 0; i <= 8; ++i)
      {
        const double x = tip - 0.17 + 0.01 * i;
        const Vec2 px = windowPixel({x, 0.0});
        if (px.x > 2 && px.y > 2 && px.x < 1277 && px.y < 797)
        {
          points.push_back({x, 0.0});
        }
      }
    }
    return points;
  }

  /// One sample of a moving (non-static) transform map -> `child` at `t` s of test time, straight
  /// into rviz's tf buffer (as a tf listener would put it).
  void tfSample(const std::string& child, double t, double x, double y, double z)
  {
    geometry_msgs::TransformStamped s = stampedTransform("map", child, x, y, z, {0.0, 0.0, 0.0, 1.0});
    s.header.stamp = start_ + ros::Duration(t);
    rviz_->manager()->getTF2BufferPtr()->setTransform(s, "projection_mask_test");
  }

  /// Shaft points of `frame` (image part) that break the rule "black where a column blocks the ray,
  /// magenta elsewhere" (points within 1 cm of a column's outline are not judged). With `report`,
  /// each is a test failure. `dark`/`lit` count the judged points.
  int mismatches(const QImage& frame, const std::vector<Column>& columns, bool report, int* dark = nullptr,
                 int* lit = nullptr) const
  {
    int wrong = 0;
    for (const Vec2& p : shaftPoints())
    {
      if (occluded(columns, p, 0.01) != occluded(columns, p, -0.01))
      {
        continue;  // within 1 cm of the column's outline: a pixel either way
      }
      const bool masked = occluded(columns, p, 0.0);
      const bool ok = sameColour(colourAt(frame, p), masked ? kBlack : kArrowMagenta, 30);
      wrong += ok ? 0 : 1;
      if (int* count = masked ? dark : lit)
      {
        ++*count;
      }
      if (report)
      {
        EXPECT_TRUE(ok) << "shaft point x = " << p.x << " should be " << (masked ? "masked" : "lit");
      }
    }
    return wrong;
  }

  /// Grabs until the shafts match `columns` (or 5 s pass), then judges that frame; returns it.
  QImage expectShafts(const std::vector<Column>& columns, int min_dark = 10, int min_lit = 10)
  {
    const QImage frame =
        imagePart(grabWhen([&](const QImage& image) { return mismatches(imagePart(image), columns, false) == 0; }));
    int dark = 0, lit = 0;
    EXPECT_EQ(mismatches(frame, columns, true, &dark, &lit), 0);
    EXPECT_GE(dark, min_dark) << "the column hides part of the path";
    EXPECT_GE(lit, min_lit);
    return frame;
  }

  ros::Time start_;
  ros::Publisher scan_pub_;
  rviz_projector::ProjectionMaskDisplay* mask_ = nullptr;
};
}  // namespace

TEST_F(ProjectionMaskTest, ArrowsAreCutExactlyWhereTheColumnBlocksTheBeam)
{
  ASSERT_TRUE(addFloorPath({{0.3, 0.0}, {1.0, 0.0}, {2.5, 0.0}}));
  grabWithArrows();
  publishScan({1.3f});  // one return straight ahead of the laser: at (1.3, 0) on the floor
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 1; }));
  // The column: 0.1 m margin around (1.3, 0), floor to 2 m. A floor point is dark when the ray from
  // the projector's optical centre to it passes through the column. Its front (x = 1.2) falls on a
  // shaft (1.18 .. 1.26): the margin shows in the pixels.
  saveShot(expectShafts({Column{{1.3, 0.0}}}, 20, 20), "mask-gap");
  EXPECT_TRUE(statusOf(mask_, "Scan").text.contains("1 returns masked"));
  // The projector's Visibility ticks the mask by default (a new projector would too).
  EXPECT_TRUE(projector_->subProp("Visibility")->subProp("Projection mask")->getValue().toBool());
}

TEST_F(ProjectionMaskTest, MainViewShowsNothingOfTheMaskUnlessAsked)
{
  rviz_->setTopDownView(1.2, 0.0, 200.0);
  ASSERT_TRUE(addFloorPath());
  const Vec2 under{1.2, 0.0};  // on a shaft (1.18 .. 1.26), right under the column
  const auto at_under = [&](const QImage& image, QRgb colour) { return sameColour(colourAt(image, under), colour, 30); };
  QImage frame = imagePart(grabWhen([&](const QImage& image) { return at_under(imagePart(image), kArrowMagenta); }));
  ASSERT_TRUE(at_under(frame, kArrowMagenta)) << "the projector lights the shaft first";
  ASSERT_TRUE(waitForMainViewFrames(3)) << "the view and the path are in the main view";
  const QImage before = rviz_->renderMainView();
  const QPoint c = rviz_->topDownPixel(1.2, 0.0);
  ASSERT_TRUE(sameColour(before.pixel(c), kArrowMagenta, 30)) << "the main view shows the shaft there";
  publishScan({1.2f});
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 1; }));
  // The projector does draw it: black over the floor point right under the column...
  frame = imagePart(grabWhen([&](const QImage& image) { return at_under(imagePart(image), kBlack); }));
  EXPECT_TRUE(at_under(frame, kBlack)) << "the projector view masks the column";
  // ...while the main view, rendered after the projector drew the mask, is unchanged.
  const QImage masked = rviz_->renderMainView();
  EXPECT_EQ(masked.pixel(c), before.pixel(c)) << "the main view draws no occluder";
  EXPECT_EQ(countColour(masked, kBlack, 10), countColour(before, kBlack, 10));
  mask_->subProp("Show in main view")->setValue(true);
  const QImage outlined = rviz_->renderMainView();
  EXPECT_NE(outlined.pixel(c), before.pixel(c)) << "Show in main view draws the translucent outline";
  mask_->subProp("Show in main view")->setValue(false);
  EXPECT_EQ(rviz_->renderMainView().pixel(c), before.pixel(c));
}

TEST_F(ProjectionMaskTest, StaleScanReleasesTheMaskAndOldScansAreDropped)
{
  ASSERT_TRUE(addFloorPath());
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
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("0 returns masked"); }));
  EXPECT_FALSE(statusOf(mask_, "Shape").present);
  mask_->subProp("Margin")->setValue(-1.0);  // clamped to 0: nothing to draw, nothing breaks
  publishScan({1.2f});
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("1 returns masked"); }))
      << "the new scan was processed";
  EXPECT_EQ(mask_->columns(), 0u);
  EXPECT_EQ(statusOf(mask_, "Shape").level, rviz::StatusProperty::Warn);
  EXPECT_TRUE(statusOf(mask_, "Shape").text.contains("Margin is 0: nothing is masked"));
  // The same scan with a margin: one column; Height 0 then masks nothing either, and says so.
  mask_->subProp("Margin")->setValue(0.1);
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 1; }));
  EXPECT_FALSE(statusOf(mask_, "Shape").present);
  mask_->subProp("Height")->setValue(0.0);
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 0; }));
  EXPECT_TRUE(statusOf(mask_, "Shape").text.contains("Height is 0: nothing is masked"));
}

TEST_F(ProjectionMaskTest, ScanWithoutStampIsDroppedAndMasksNothing)
{
  ASSERT_TRUE(addFloorPath());
  grabWithArrows();
  publishScan({1.2f}, ros::Time());
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("no stamp"); }));
  EXPECT_EQ(statusOf(mask_, "Scan").level, rviz::StatusProperty::Warn);
  EXPECT_EQ(mask_->columns(), 0u);
  expectShafts({}, 0, 20);  // every shaft point lit
}

TEST_F(ProjectionMaskTest, ScanIsPlacedByTheTransformAtItsOwnStamp)
{
  ASSERT_TRUE(addFloorPath());
  grabWithArrows();
  // The scanner moves: x = 0 at 0.1 s, x = 0.5 at 0.3 s (tf samples, not static).
  tfSample("moving_laser", 0.1, 0.0, 0.0, 0.3);
  tfSample("moving_laser", 0.3, 0.5, 0.0, 0.3);
  at(0.35);
  publishScan({1.2f}, start_ + ros::Duration(0.1), "moving_laser");  // taken at 0.1 s, arriving late
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("1 returns masked"); }));
  ASSERT_EQ(mask_->columns(), 1u);
  // Where the pose at 0.1 s puts the return: (1.2, 0), not (1.7, 0) as the newest pose would; the
  // shafts between 1.1 and 1.6 tell the two apart.
  expectShafts({Column{{1.2, 0.0}}}, 20, 20);
}

namespace
{
/// A PointCloud2 of float x, y, z (and 4 unused bytes) per point in `rows` rows, each row followed
/// by the bytes of `padding` (a point no reader may take: row_step is larger than width x point_step).
sensor_msgs::PointCloud2 makeCloud(const std::string& frame, const ros::Time& stamp, const std::vector<Vec3>& points,
                                   unsigned rows, const Vec3& padding, bool with_z = true)
{
  sensor_msgs::PointCloud2 cloud;
  cloud.header.frame_id = frame;
  cloud.header.stamp = stamp;
  cloud.height = rows;
  cloud.width = static_cast<unsigned>(points.size() / rows);
  const char* names[3] = {"x", "y", "z"};
  for (unsigned i = 0; i < (with_z ? 3u : 2u); ++i)
  {
    sensor_msgs::PointField f;
    f.name = names[i];
    f.offset = 4 * i;
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    cloud.fields.push_back(f);
  }
  cloud.point_step = 16;
  cloud.row_step = cloud.width * cloud.point_step + cloud.point_step;
  cloud.data.resize(std::size_t(cloud.row_step) * rows, 0);
  const auto put = [&](std::size_t at, const Vec3& p) {
    const float xyz[3] = {float(p.x), float(p.y), float(p.z)};
    std::memcpy(&cloud.data[at], xyz, sizeof(xyz));
  };
  for (unsigned r = 0; r < rows; ++r)
  {
    for (unsigned c = 0; c < cloud.width; ++c)
    {
      put(std::size_t(r) * cloud.row_step + c * cloud.point_step, points[r * cloud.width + c]);
    }
    put(std::size_t(r) * cloud.row_step + cloud.width * cloud.point_step, padding);
  }
  cloud.is_dense = true;
  return cloud;
}
}  // namespace

TEST_F(ProjectionMaskTest, PointCloudMasksByCellsOnceItsTransformArrives)
{
  ros::Publisher cloud_pub = nh_.advertise<sensor_msgs::PointCloud2>("/test/cloud", 2);
  mask_->subProp("Point cloud topic")->setValue("/test/cloud");
  ASSERT_TRUE(waitFor([&] { return cloud_pub.getNumSubscribers() > 0; }));
  ASSERT_TRUE(addFloorPath());
  grabWithArrows();
  // A person-like blob in map: points on a 0.2 m radius cylinder around (1.55, 0.013), 0.1 .. 1.7 m
  // high (the centre keeps every point at least 9 mm from a 0.1 m cell's edge). Then what must not
  // mask, in front of it: points on the floor (z = 1 cm < 3 cm) and above Height (2.3 m).
  const Vec2 centre{1.55, 0.013};
  std::vector<Vec3> in_map;
  for (int k = 1; k <= 17; ++k)
  {
    for (int i = 0; i < 20; ++i)
    {
      const double a = 2.0 * M_PI * i / 20.0;
      in_map.push_back(Vec3{centre.x + 0.2 * std::cos(a), centre.y + 0.2 * std::sin(a), 0.1 * k});
    }
  }
  const std::size_t blob = in_map.size();
  for (int i = 0; i < 8; ++i)
  {
    in_map.push_back(Vec3{0.72 + 0.01 * i, 0.013, 0.01});
    in_map.push_back(Vec3{0.97 + 0.01 * i, 0.013, 2.3});
  }
  // The sensor's frame is map moved by (0.4, 0, 0.5): the cloud is in that frame.
  const Vec3 sensor{0.4, 0.0, 0.5};
  std::vector<Vec3> in_sensor;
  for (const Vec3& p : in_map)
  {
    in_sensor.push_back(Vec3{p.x - sensor.x, p.y - sensor.y, p.z - sensor.z});
  }
  // Row padding holding a point at (0.72, 0.013, 0.5) in map: masked if row_step were ignored.
  const Vec3 decoy{0.72 - sensor.x, 0.013 - sensor.y, 0.5 - sensor.z};
  at(0.1);
  cloud_pub.publish(makeCloud("test_depth", ros::Time::now(), in_sensor, 2, decoy));
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Point cloud").text.contains("Waiting for the transform"); }));
  EXPECT_EQ(mask_->columns(), 0u);
  tfSample("test_depth", 0.0, sensor.x, sensor.y, sensor.z);  // tf arrives after the cloud
  tfSample("test_depth", 0.2, sensor.x, sensor.y, sensor.z);
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Point cloud").text.contains("points masked"); }));
  EXPECT_TRUE(statusOf(mask_, "Point cloud").text.startsWith(QString("%1 points masked").arg(blob)))
      << statusOf(mask_, "Point cloud").text.toStdString();
  // The expected columns, by the documented rule: cells [k 0.1, (k + 1) 0.1) (cell = max(Margin,
  // 0.05)), one column per occupied cell at its centre, half-width Margin + cell / 2.
  std::set<std::pair<long, long>> cells;
  for (std::size_t i = 0; i < blob; ++i)
  {
    cells.emplace(std::lround(std::floor(in_map[i].x / 0.1)), std::lround(std::floor(in_map[i].y / 0.1)));
  }
  std::vector<Column> columns;
  for (const auto& c : cells)
  {
    columns.push_back(Column{{(double(c.first) + 0.5) * 0.1, (double(c.second) + 0.5) * 0.1}, 0.1 + 0.05, 2.0});
  }
  EXPECT_EQ(mask_->columns(), columns.size());
  // The blob's front (x = 1.35, cell 1.3 .. 1.4) masks from x = 1.2 on: on the shaft 1.18 .. 1.26.
  expectShafts(columns, 20, 20);
  // A cloud without z: an error, the cloud dropped, rviz going on (the projector still draws).
  cloud_pub.publish(makeCloud("test_depth", ros::Time::now(), in_sensor, 2, decoy, false));
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Point cloud").text.contains("Unusable cloud"); }));
  EXPECT_EQ(statusOf(mask_, "Point cloud").level, rviz::StatusProperty::Error);
  EXPECT_TRUE(statusOf(mask_, "Point cloud").text.contains("no field 'z'"));
  EXPECT_GT(countColour(grabWithArrows(), kArrowMagenta), 100);
}

TEST_F(ProjectionMaskTest, AScanOf200000ReturnsIsMaskedByCellsWithinTheColumnBudget)
{
  // The README's budget: a scan of more than 20,000 returns is masked by cells of side
  // max(Margin, 5 cm), one column per occupied cell, at most 20,000 columns.
  ASSERT_TRUE(addFloorPath());
  grabWithArrows();
  sensor_msgs::LaserScan scan;
  scan.header.frame_id = "test_laser";  // at (0, 0, 0.3) in map
  scan.range_min = 0.05f;
  scan.range_max = 20.0f;
  // 1. 200,000 returns at 1.55 m within 5 .. 7 mrad: all on the floor in x 1.5499 .. 1.55, y 7.7 ..
  //    10.9 mm, one 0.1 m cell [1.5, 1.6) x [0, 0.1): one column at its centre, 0.1 + 0.05 wide.
  scan.angle_min = 0.005f;
  scan.angle_increment = 1e-8f;
  scan.angle_max = scan.angle_min + scan.angle_increment * 199999.0f;
  scan.ranges.assign(200000, 1.55f);
  scan.header.stamp = ros::Time::now();
  scan_pub_.publish(scan);
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("cells"); }))
      << statusOf(mask_, "Scan").text.toStdString();
  EXPECT_EQ(mask_->columns(), 1u);
  EXPECT_EQ(statusOf(mask_, "Scan").level, rviz::StatusProperty::Ok);
  EXPECT_TRUE(statusOf(mask_, "Scan").text.startsWith("200000 returns (more than 20000): masked by 1 cells of 0.1 m"))
      << statusOf(mask_, "Scan").text.toStdString();
  expectShafts({Column{{1.55, 0.05}, 0.1 + 0.05, 2.0}}, 5, 20);

  // 2. 200,000 returns all round, at ranges spread over 0.3 .. 9.9 m: about 30,000 occupied cells
  //    (counted here by hand), more than the budget: 20,000 columns and a warning saying so.
  scan.angle_min = -3.14159f;
  scan.angle_increment = 2.0f * 3.14159f / 200000.0f;
  scan.angle_max = scan.angle_min + scan.angle_increment * 199999.0f;
  std::set<std::pair<long, long>> cells;
  for (std::size_t i = 0; i < scan.ranges.size(); ++i)
  {
    const double golden = 0.6180339887498949 * double(i);
    scan.ranges[i] = static_cast<float>(0.3 + 9.6 * (golden - std::floor(golden)));
    const double a = double(scan.angle_min) + double(scan.angle_increment) * double(i);
    const double r = double(scan.ranges[i]);
    cells.emplace(std::lround(std::floor(r * std::cos(a) / 0.1)), std::lround(std::floor(r * std::sin(a) / 0.1)));
  }
  ASSERT_GT(cells.size(), 25000u) << "the scan must occupy more cells than the budget";
  scan.header.stamp = ros::Time::now();
  scan_pub_.publish(scan);
  ASSERT_TRUE(waitFor([&] { return statusOf(mask_, "Scan").text.contains("only the first"); }))
      << statusOf(mask_, "Scan").text.toStdString();
  EXPECT_EQ(mask_->columns(), 20000u);
  EXPECT_EQ(statusOf(mask_, "Scan").level, rviz::StatusProperty::Warn);
  EXPECT_TRUE(statusOf(mask_, "Scan").text.contains("only the first 20000 cells"));
  // rviz goes on: the next ordinary scan is masked as before.
  publishScan({1.3f});
  ASSERT_TRUE(waitFor([&] { return mask_->columns() == 1; }));
  EXPECT_TRUE(statusOf(mask_, "Scan").text.contains("1 returns masked"));
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
