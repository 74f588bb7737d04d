// ProjectedPath's Corridor (issue 25) in a real rviz, judged on the projector output's pixels: the
// edges of a round robot's corridor on a straight path, of a rectangular robot turning round an arc
// (its outer edge sqrt(0.4^2 + (R + 0.3)^2) from the turn's centre, not R + 0.3: worked out by
// hand below), the band blended once where its pieces overlap, the footprint from a PolygonStamped
// topic in another frame; statuses for bad polygons and a missing footprint; the properties saved and
// loaded, and a config without the group. Expected places come from hand geometry and image_geometry
// (windowPixel), never from the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <vector>

#include <geometry_msgs/PolygonStamped.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/properties/property.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>

#include "projector_test_fixture.h"
#include "rviz_projector/displays/projected_path_display.h"

using namespace rviz_projector_test;

namespace
{
constexpr double kRobotX = 0.3;                // the robot (base_link) and the path's start
const QRgb kYellow = qRgb(255, 200, 0);        // the default Color, opaque (edges)
const QRgb kYellowBand = qRgb(77, 60, 0);      // 0.3 of it over black (the band, Alpha 0.3), once
const char* kRectangle = "[[0.4, 0.3], [-0.2, 0.3], [-0.2, -0.3], [0.4, -0.3]]";

std::vector<Vec2> straightPath(double end)
{
  return lineAlongX(kRobotX, end);
}

/// Turning left round (kRobotX, radius) from the robot, `angle` radians, a pose every 2 cm.
std::vector<Vec2> arcPath(double radius, double angle)
{
  std::vector<Vec2> points;
  const int n = int(std::ceil(radius * angle / 0.02));
  for (int i = 0; i <= n; ++i)
  {
    const double a = angle * i / n;
    points.push_back({kRobotX + radius * std::sin(a), radius - radius * std::cos(a)});
  }
  return points;
}

class CorridorTest : public ProjectorSceneTest
{
protected:
  void SetUp() override
  {
    ProjectorSceneTest::SetUp();
    footprint_pub_ = nh_.advertise<geometry_msgs::PolygonStamped>("/test/footprint", 2, true);
  }

  /// `points` from the robot (standing at x 0.3 facing +x), the corridor on (Length `length`).
  bool pathWithCorridor(const std::vector<Vec2>& points, double length)
  {
    path_ = addFloorPathFromRobot(points, kRobotX, 0.0);
    if (path_ == nullptr)
    {
      return false;
    }
    corridor()->subProp("Length")->setValue(length);
    corridor()->setValue(true);
    return true;
  }

  rviz::Property* corridor() { return path_->subProp("Corridor"); }

  QRgb colourAt(const QImage& frame, const Vec2& floor) const
  {
    const Vec2 px = windowPixel(floor);
    return frame.pixel(int(std::lround(px.x)), int(std::lround(px.y)));
  }

  bool yellowAt(const QImage& frame, const Vec2& floor, QRgb colour = kYellow) const
  {
    return sameColour(colourAt(frame, floor), colour, 40);
  }

  QImage grabUntil(const std::function<bool(const QImage&)>& ok) { return imagePart(grabWhen(ok, 8.0)); }

  rviz_projector::ProjectedPathDisplay* path_ = nullptr;
  ros::Publisher footprint_pub_;
};
}  // namespace

TEST_F(CorridorTest, RoundRobotOnAStraightPathHasTwoEdgesItsRadiusAside)
{
  ASSERT_TRUE(pathWithCorridor(straightPath(2.5), 1.0));
  // Radius 0.3 (default), 3 cm lines centred on the edges: y = +-0.3 from x = 0.3 to 1.3; the caps
  // behind the robot and at the far end are not drawn.
  const QImage frame = grabUntil([&](const QImage& image) { return yellowAt(image, {0.8, 0.3}); });
  saveShot(frame, "cues-corridor");
  for (const double x : {0.6, 0.9, 1.2})  // the projector's view starts at x 0.5
  {
    for (const double y : {0.3, -0.3})
    {
      EXPECT_TRUE(yellowAt(frame, {x, y})) << x << ", " << y << ": " << describe(colourAt(frame, {x, y}));
    }
    EXPECT_TRUE(sameColour(colourAt(frame, {x, 0.34}), kBlack, 20)) << "outside the line at x = " << x;
    EXPECT_TRUE(sameColour(colourAt(frame, {x, 0.2}), kBlack, 20)) << "inside the corridor at x = " << x;
  }
  EXPECT_TRUE(sameColour(colourAt(frame, {1.4, 0.3}), kBlack, 20)) << "Length 1 m: nothing beyond x = 1.3";
  EXPECT_TRUE(sameColour(colourAt(frame, {1.5, 0.0}), kArrowMagenta, 60) ||
              sameColour(colourAt(frame, {1.5, 0.0}), kBlack, 20))
      << "no cap across the path at the far end";
  EXPECT_GT(countColour(frame, kArrowMagenta), 100) << "the arrows are still drawn";
  EXPECT_EQ(statusOf(path_, "Corridor").level, rviz::StatusProperty::Ok);
  EXPECT_GT(path_->corridorTriangleCount(), 0u);
}

TEST_F(CorridorTest, RectangleTurningRoundAnArcSweepsWiderOutsideThanItsHalfWidth)
{
  const double radius = 1.0;
  ASSERT_TRUE(pathWithCorridor(arcPath(radius, 1.4), 1.4));
  corridor()->subProp("Footprint")->setValue("Polygon");
  corridor()->subProp("Polygon")->setValue(kRectangle);
  // Turning left round (0.3, 1): the outer (right) edge is traced by the front right corner,
  // sqrt(0.4^2 + 1.3^2) = 1.3601 m from the centre; the inner edge by the middle of the left side,
  // 1 - 0.3 = 0.7 m. A fixed offset of the centre line would put the outer edge at 1.3 m.
  const Vec2 centre{kRobotX, radius};
  const double outer = std::sqrt(0.4 * 0.4 + 1.3 * 1.3);
  auto at = [&](double r, double angle) { return centre + Vec2{r * std::sin(angle), -r * std::cos(angle)}; };
  const QImage frame = grabUntil([&](const QImage& image) { return yellowAt(image, at(outer, 0.6)); });
  saveShot(frame, "cues-corridor-turn");
  for (const double angle : {0.5, 0.7, 0.9})
  {
    EXPECT_TRUE(yellowAt(frame, at(outer, angle))) << "outer edge at " << angle << " rad: "
                                                   << describe(colourAt(frame, at(outer, angle)));
    EXPECT_TRUE(sameColour(colourAt(frame, at(1.3, angle)), kBlack, 20)) << "not a fixed 0.3 m offset, " << angle;
    EXPECT_TRUE(yellowAt(frame, at(0.7, angle))) << "inner edge at " << angle << " rad: "
                                                 << describe(colourAt(frame, at(0.7, angle)));
    EXPECT_TRUE(sameColour(colourAt(frame, at(0.75, angle)), kBlack, 20)) << "inside, " << angle;
  }
  EXPECT_EQ(statusOf(path_, "Corridor").level, rviz::StatusProperty::Ok);
}

TEST_F(CorridorTest, BandIsFilledOnceWhereItsPiecesOverlap)
{
  ASSERT_TRUE(pathWithCorridor(arcPath(1.0, 1.4), 1.4));
  corridor()->subProp("Style")->setValue("Band");
  const Vec2 centre{kRobotX, 1.0};
  auto at = [&](double r, double angle) { return centre + Vec2{r * std::sin(angle), -r * std::cos(angle)}; };
  const QImage frame = grabUntil([&](const QImage& image) { return yellowAt(image, at(1.2, 0.6), kYellowBand); });
  saveShot(frame, "cues-corridor-band");
  // Round robot, radius 0.3: the band spans 0.7 .. 1.3 from the turn's centre. Everywhere in it
  // (beside the arrows, 6 cm either side of the path) one layer of 0.3 alpha, however many pieces.
  for (const double angle : {0.3, 0.6, 0.9, 1.2})
  {
    for (const double r : {0.75, 0.85, 1.15, 1.25})
    {
      EXPECT_TRUE(sameColour(colourAt(frame, at(r, angle)), kYellowBand, 12))
          << r << " m, " << angle << " rad: " << describe(colourAt(frame, at(r, angle)));
    }
    EXPECT_TRUE(sameColour(colourAt(frame, at(1.33, angle)), kBlack, 20)) << "outside, " << angle;
  }
}

TEST_F(CorridorTest, FootprintFromATopicInAnotherFrame)
{
  ASSERT_TRUE(pathWithCorridor(straightPath(2.5), 0.8));
  corridor()->subProp("Footprint")->setValue("Topic");
  corridor()->subProp("Footprint topic")->setValue("/test/footprint");
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Corridor").text.contains("No footprint received yet"); }));
  // As move_base publishes it: the rectangle where the robot is (x 0.3), in the map frame.
  geometry_msgs::PolygonStamped msg;
  msg.header.frame_id = "map";
  msg.header.stamp = ros::Time::now();
  for (const Vec2& p : std::vector<Vec2>{{0.7, 0.3}, {0.1, 0.3}, {0.1, -0.3}, {0.7, -0.3}})
  {
    geometry_msgs::Point32 q;
    q.x = float(p.x);
    q.y = float(p.y);
    msg.polygon.points.push_back(q);
  }
  footprint_pub_.publish(msg);
  // The rectangle swept from x 0.3 to 1.1: edges at y = +-0.3 from x = 0.1 to 1.5 (in view from 0.5).
  const QImage frame = grabUntil([&](const QImage& image) { return yellowAt(image, {1.45, 0.3}); });
  for (const double x : {0.6, 1.0, 1.45})
  {
    EXPECT_TRUE(yellowAt(frame, {x, 0.3})) << x << ": " << describe(colourAt(frame, {x, 0.3}));
    EXPECT_TRUE(yellowAt(frame, {x, -0.3})) << x;
  }
  EXPECT_TRUE(sameColour(colourAt(frame, {1.55, 0.3}), kBlack, 20)) << "the robot's front at the end: x 1.5";
  EXPECT_EQ(statusOf(path_, "Corridor").level, rviz::StatusProperty::Ok);
  EXPECT_GT(path_->footprintMessages(), 0u);

  // Moved into the Robot frame once per message (its outline at its stamp cannot change), though
  // every drawing asks for it: a new Length draws again at once, with the same outline.
  const std::size_t moved = path_->footprintTransforms();
  EXPECT_GE(moved, 1u);
  corridor()->subProp("Length")->setValue(0.7);
  EXPECT_EQ(path_->footprintTransforms(), moved) << "the same message moved into the Robot frame again";
  // A zero stamp means the latest transform, which follows the robot: moved again for each drawing.
  msg.header.stamp = ros::Time();
  footprint_pub_.publish(msg);
  ASSERT_TRUE(waitFor([&] { return path_->footprintTransforms() > moved; }));
  const std::size_t latest = path_->footprintTransforms();
  corridor()->subProp("Length")->setValue(0.8);
  EXPECT_GT(path_->footprintTransforms(), latest) << "a zero stamp's outline kept instead of following tf";

  // An empty polygon: refused, the arrows keep running.
  msg.polygon.points.clear();
  footprint_pub_.publish(msg);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Corridor").level == rviz::StatusProperty::Error; }));
  EXPECT_TRUE(statusOf(path_, "Corridor").text.contains("0 points")) << statusOf(path_, "Corridor").text.toStdString();
  const auto none = [&](const QImage& image) { return countColour(image, kYellow, 40) == 0; };
  EXPECT_TRUE(none(grabUntil(none)));
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100);
}

TEST_F(CorridorTest, BadFootprintsSayWhyAndDrawNothing)
{
  ASSERT_TRUE(pathWithCorridor(straightPath(2.5), 1.0));
  const auto none = [&](const QImage& image) { return countColour(image, kYellow, 40) == 0; };
  corridor()->subProp("Footprint")->setValue("Polygon");
  for (const auto& bad : std::vector<std::pair<const char*, const char*>>{
           {"[[0, 0], [2, 2], [2, 0], [0, 1]]", "cross"},
           {"[[0.4, 0.3], [0.1]]", "cannot read"},
           {"[[0.4, 0.3], [0.1, 0.2]]", "2 points"},
           {"[[0, 0], [nan, 1], [1, 0]]", "finite"}})
  {
    corridor()->subProp("Polygon")->setValue(bad.first);
    EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Corridor").text.contains(bad.second); }))
        << bad.first << ": " << statusOf(path_, "Corridor").text.toStdString();
    EXPECT_EQ(statusOf(path_, "Corridor").level, rviz::StatusProperty::Error) << bad.first;
    EXPECT_TRUE(none(grabUntil(none))) << bad.first;
  }
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100) << "the arrows keep running";
  corridor()->subProp("Polygon")->setValue(kRectangle);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Corridor").level == rviz::StatusProperty::Ok; }));
  corridor()->setValue(false);
  EXPECT_TRUE(none(grabUntil(none)));
  EXPECT_TRUE(waitFor([&] { return !statusOf(path_, "Corridor").present; }));
}

namespace
{
class CorridorConfigTest : public RvizTest
{
};
}  // namespace

TEST_F(CorridorConfigTest, PropertiesAreSavedAndLoaded)
{
  const std::map<std::string, QVariant> values = {
      {"Footprint", "Topic"},   {"Radius", 0.45},     {"Polygon", "[[1, 1], [-1, 1], [0, -1]]"},
      {"Footprint topic", "/move_base/global_costmap/footprint"},   {"Length", 2.5},
      {"Style", "Band"},        {"Edge width", 0.05}, {"Color", QColor(10, 20, 30)}, {"Alpha", 0.6}};
  std::map<std::string, std::string> shown = expectGroupSavedAndLoaded("Corridor", values);
  EXPECT_EQ(shown["Style"], "Band");
  EXPECT_EQ(shown["Footprint"], "Topic");
}

TEST_F(CorridorConfigTest, AConfigWithoutTheGroupLoadsWithItOffAndBadValuesAreReported)
{
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readString(config, R"(
Displays:
  - Class: rviz_projector/ProjectedPath
    Name: Saved before the corridor existed
    Enabled: true
    Topic: /test/plan
  - Class: rviz_projector/ProjectedPath
    Name: Bad corridor
    Enabled: true
    Topic: /test/plan
    Corridor:
      Value: true
      Footprint: Hexagon
      Length: -3
      Edge width: abc
      Style: Dotted
)");
  ASSERT_FALSE(reader.error());
  rviz_->manager()->load(config);
  rviz::DisplayGroup* root = rviz_->manager()->getRootDisplayGroup();
  ASSERT_EQ(root->numDisplays(), 2);
  rviz::Display* old = root->getDisplayAt(0);
  EXPECT_FALSE(old->subProp("Corridor")->getValue().toBool());
  EXPECT_EQ(old->subProp("Corridor")->subProp("Footprint")->getValue().toString().toStdString(), "Radius");
  EXPECT_NEAR(old->subProp("Corridor")->subProp("Length")->getValue().toDouble(), 3.0, 1e-6);
  spinFor(0.2);  // statuses settle (the absence of a status is the verdict)
  EXPECT_FALSE(statusOf(old, "Corridor").present);
  EXPECT_FALSE(statusOf(old, "Config").present) << statusOf(old, "Config").text.toStdString();

  rviz::Display* bad = root->getDisplayAt(1);
  rviz::Property* group = bad->subProp("Corridor");
  EXPECT_EQ(group->subProp("Footprint")->getValue().toString().toStdString(), "Radius");
  EXPECT_EQ(group->subProp("Style")->getValue().toString().toStdString(), "Edges");
  EXPECT_GT(group->subProp("Length")->getValue().toDouble(), 0.0);
  const Status s = statusOf(bad, "Config");
  ASSERT_TRUE(s.present);
  for (const char* name : {"Footprint: 'Hexagon' -> Radius", "Length: '-3'", "Edge width: 'abc'", "Style: 'Dotted' -> Edges"})
  {
    EXPECT_NE(s.text.indexOf(name), -1) << name << " missing in: " << s.text.toStdString();
  }
}
