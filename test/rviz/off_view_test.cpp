// ProjectedPath's Off-view cue (issue 25 part 3) in a real rviz, judged on the projector output's
// pixels. The projector of ProjectorSceneTest (1280x800, f 1300, 1.2 m up, pitched down 0.9 rad,
// looking along +x) lights a trapezoid from x ~0.47 to ~1.75; the robot (base_link) stands at x 0.3,
// just behind it. Where the cue must be comes from hand geometry on the lit area that image_geometry
// gives (the floor under the image's outer pixel edges), never from the code under test:
// - edge arrow: its tip at the point nearest the target (the window's end) of the lit area shrunk
//   by the margin (0.15 m: each edge moved inwards, the corners where the moved edges meet),
//   pointing along the path there;
// - turn in place: the glyph on the lit area's centroid (shoelace), its head on the turn's side;
// - final approach: the tip at the shrunk area's point nearest the destination, pointing at it;
// - nothing while the path is visible, and the show/hide hysteresis; the cue keeps off the arrows
//   that are drawn (with the Horizon from the robot on, not off the path behind it);
// - bad input: no CameraInfo, zeros, NaN, a frame tf does not know, no robot: a status, nothing drawn;
// - the properties saved and loaded, a config without the group.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <vector>

#include <nav_msgs/Path.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/properties/property.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>

#include "projector_test_fixture.h"
#include "robustness_helpers.h"
#include "rviz_projector/displays/projected_path_display.h"

using namespace rviz_projector_test;

namespace
{
constexpr double kRobotX = 0.3;          // the robot (base_link) and the paths' start
constexpr double kMargin = 0.15;         // OffViewParameters' margin (the tip's distance from the edge)
const QRgb kCyan = qRgb(0, 200, 255);    // the default Color, opaque
constexpr const char* kOwnInfo = "/test/off_view/camera_info";

/// Straight pieces through `corners`, a point every 5 cm.
std::vector<Vec2> polyline(const std::vector<Vec2>& corners)
{
  std::vector<Vec2> points{corners.front()};
  for (std::size_t i = 1; i < corners.size(); ++i)
  {
    const Vec2 a = corners[i - 1], b = corners[i];
    const int n = std::max(1, int(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / 0.05)));
    for (int k = 1; k <= n; ++k)
    {
      points.push_back(Vec2{a.x + (b.x - a.x) * k / n, a.y + (b.y - a.y) * k / n});
    }
  }
  return points;
}

Vec2 add(const Vec2& a, const Vec2& b, double s = 1.0) { return Vec2{a.x + s * b.x, a.y + s * b.y}; }
double crossOf(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }

/// Signed area (> 0: counter-clockwise).
double area(const std::vector<Vec2>& p)
{
  double twice = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    twice += crossOf(p[i], p[(i + 1) % p.size()]);
  }
  return 0.5 * twice;
}

/// Area centroid (shoelace).
Vec2 centroidOf(const std::vector<Vec2>& p)
{
  double sx = 0.0, sy = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec2& a = p[i];
    const Vec2& b = p[(i + 1) % p.size()];
    sx += (a.x + b.x) * crossOf(a, b);
    sy += (a.y + b.y) * crossOf(a, b);
  }
  const double a6 = 6.0 * area(p);
  return Vec2{sx / a6, sy / a6};
}

/// A convex polygon with every edge moved `m` inwards; its corners where neighbouring moved edges meet.
std::vector<Vec2> inset(const std::vector<Vec2>& p, double m)
{
  const double sign = area(p) > 0.0 ? 1.0 : -1.0;  // inwards: left of a counter-clockwise edge
  const std::size_t n = p.size();
  std::vector<Vec2> from(n), dir(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec2 d{p[(i + 1) % n].x - p[i].x, p[(i + 1) % n].y - p[i].y};
    const double l = std::hypot(d.x, d.y);
    dir[i] = Vec2{d.x / l, d.y / l};
    from[i] = add(p[i], Vec2{-dir[i].y * sign, dir[i].x * sign}, m);
  }
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < n; ++i)
  {
    const std::size_t j = (i + n - 1) % n;  // edge j ends where edge i starts
    // from[j] + t dir[j] = from[i] + s dir[i] (edges in line: where edge i's moved start is)
    const Vec2 w{from[i].x - from[j].x, from[i].y - from[j].y};
    const double turn = crossOf(dir[j], dir[i]);
    out.push_back(std::abs(turn) < 1e-9 ? from[i] : add(from[j], dir[j], crossOf(w, dir[i]) / turn));
  }
  return out;
}

/// The point of a convex polygon's boundary nearest to `q` (q outside it).
Vec2 nearestOn(const std::vector<Vec2>& p, const Vec2& q)
{
  Vec2 best = p.front();
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const Vec2 a = p[i], b = p[(i + 1) % p.size()];
    const Vec2 ab{b.x - a.x, b.y - a.y};
    const double t = std::clamp(((q.x - a.x) * ab.x + (q.y - a.y) * ab.y) / (ab.x * ab.x + ab.y * ab.y), 0.0, 1.0);
    const Vec2 c = add(a, ab, t);
    const double d = std::hypot(q.x - c.x, q.y - c.y);
    if (d < best_d)
    {
      best_d = d;
      best = c;
    }
  }
  return best;
}

Vec2 unit(const Vec2& v)
{
  const double l = std::hypot(v.x, v.y);
  return Vec2{v.x / l, v.y / l};
}

class OffViewTest : public ProjectorSceneTest
{
protected:
  /// The robot at (kRobotX, 0) facing `yaw`, `points` as the path, the Off-view cue on with
  /// `info_topic` (default: the ProjectorCamera's own CameraInfo topic).
  bool pathWithCue(const std::vector<Vec2>& points, double yaw, const char* info_topic = kInfoTopic)
  {
    path_ = addFloorPathFromRobot(points, kRobotX, yaw);
    if (path_ == nullptr)
    {
      return false;
    }
    cue()->subProp("Projector info topic")->setValue(info_topic);
    cue()->setValue(true);
    return true;
  }

  void publishPath(const std::vector<Vec2>& points)
  {
    std::vector<Vec3> floor;
    for (const Vec2& p : points)
    {
      floor.push_back(Vec3{p.x, p.y, 0.0});
    }
    path_pub_.publish(makePath("map", floor));
  }

  rviz::Property* cue() { return path_->subProp("Off-view cue"); }

  /// The lit area by image_geometry (cv::undistortPoints for a lens with D): the floor under the
  /// image's outer pixel edges, `per_edge` points along each edge (an ideal lens: its corners do).
  std::vector<Vec2> litArea(const sensor_msgs::CameraInfo& info, int per_edge = 1) const
  {
    const PixelOracle oracle(info, kDemoMount);
    const double w = oracle.imageWidth(), h = oracle.imageHeight();
    const std::vector<Vec2> corners{{-0.5, -0.5}, {w - 0.5, -0.5}, {w - 0.5, h - 0.5}, {-0.5, h - 0.5}};
    std::vector<Vec2> lit;
    for (std::size_t c = 0; c < 4; ++c)
    {
      const Vec2 a = corners[c], b = corners[(c + 1) % 4];
      for (int k = 0; k < per_edge; ++k)
      {
        lit.push_back(oracle.floorPoint(add(a, Vec2{b.x - a.x, b.y - a.y}, double(k) / per_edge)));
      }
    }
    return lit;
  }
  std::vector<Vec2> litArea() const { return litArea(info_); }

  QRgb colourAt(const QImage& frame, const Vec2& floor) const
  {
    const Vec2 px = windowPixel(floor);
    return frame.pixel(int(std::lround(px.x)), int(std::lround(px.y)));
  }
  bool cyanAt(const QImage& frame, const Vec2& floor) const { return sameColour(colourAt(frame, floor), kCyan, 40); }
  bool blackAt(const QImage& frame, const Vec2& floor) const { return sameColour(colourAt(frame, floor), kBlack, 20); }
  int cyanPixels(const QImage& frame) const { return countColour(frame, kCyan, 40); }

  QImage grabUntil(const std::function<bool(const QImage&)>& ok) { return imagePart(grabWhen(ok, 8.0)); }
  bool statusSays(const char* text)
  {
    return waitFor([&] { return statusOf(path_, "Off-view cue").text.contains(text); }, 8.0);
  }
  std::string status() { return statusOf(path_, "Off-view cue").text.toStdString(); }
  /// No cue pixel in the frames once the status says `text` (the display has judged the new input).
  /// "path visible" is the design working: an Ok status, not a warning.
  void expectNothingDrawn(const char* text)
  {
    EXPECT_TRUE(statusSays(text)) << status();
    if (std::string(text) == "path visible")
    {
      EXPECT_EQ(statusOf(path_, "Off-view cue").level, rviz::StatusProperty::Ok) << status();
    }
    const auto none = [&](const QImage& image) { return cyanPixels(image) == 0; };
    const QImage frame = grabUntil(none);
    EXPECT_EQ(cyanPixels(frame), 0) << text;
    EXPECT_EQ(path_->offViewTriangleCount(), 0u) << text;
  }

  /// An arrow from its tip back along `direction` (0.3 m long, 0.12 m head, 0.06 m shaft): its
  /// centre line coloured from near the tip to near the tail, black just beyond the tip and beside it.
  void expectArrow(const QImage& frame, const Vec2& tip, const Vec2& direction)
  {
    const Vec2 across{-direction.y, direction.x};
    for (const double back : {0.04, 0.12, 0.2, 0.27})
    {
      const Vec2 p = add(tip, direction, -back);
      EXPECT_TRUE(cyanAt(frame, p)) << back << " m behind the tip (" << p.x << ", " << p.y
                                    << "): " << describe(colourAt(frame, p));
    }
    const Vec2 beyond = add(tip, direction, 0.04);
    EXPECT_TRUE(blackAt(frame, beyond)) << "beyond the tip: " << describe(colourAt(frame, beyond));
    for (const double side : {-0.08, 0.08})
    {
      const Vec2 p = add(add(tip, direction, -0.22), across, side);
      EXPECT_TRUE(blackAt(frame, p)) << "beside the shaft (" << side << "): " << describe(colourAt(frame, p));
    }
  }

  rviz_projector::ProjectedPathDisplay* path_ = nullptr;
};

/// Leaves to the robot's left (+y) at x 0.3, outside the lit area, 2.5 m long.
const std::vector<Vec2> kLeftwards = polyline({{kRobotX, 0.0}, {kRobotX, 2.5}});
/// Straight ahead through the lit area.
const std::vector<Vec2> kAhead = polyline({{kRobotX, 0.0}, {2.5, 0.0}});
}  // namespace

TEST_F(OffViewTest, PathLeavingTheLitAreaGetsAnEdgeArrowAndNoneOnceVisible)
{
  ASSERT_TRUE(pathWithCue(kLeftwards, M_PI / 2));
  // The window is the next 1.5 m: it ends at (0.3, 1.5); the tip is the shrunk area's point nearest
  // it, and the arrow points along the path there (+y).
  const std::vector<Vec2> lit = litArea();
  const Vec2 tip = nearestOn(inset(lit, kMargin), Vec2{kRobotX, 1.5});
  const Vec2 direction{0.0, 1.0};
  const QImage frame = grabUntil([&](const QImage& image) { return cyanAt(image, add(tip, direction, -0.15)); });
  saveShot(frame, "cues-off-view-edge");
  expectArrow(frame, tip, direction);
  EXPECT_TRUE(statusSays("edge arrow")) << status();
  EXPECT_EQ(statusOf(path_, "Off-view cue").level, rviz::StatusProperty::Ok);
  EXPECT_GT(path_->offViewTriangleCount(), 0u);
  // Nothing changes: no upload and no new cue, however many frames rviz draws.
  const std::size_t builds = path_->meshBuilds(), cues = path_->offViewSource().builds();
  EXPECT_TRUE(waitForMainViewFrames(20));
  EXPECT_EQ(path_->meshBuilds(), builds) << "the same cue uploaded again";
  EXPECT_EQ(path_->offViewSource().builds(), cues) << "the same cue worked out again";

  // The robot turns to the path straight ahead: the path is in view, the cue goes.
  publishStaticTransform("map", "base_link", kRobotX, 0.0, 0.0, 0.0);
  publishPath(kAhead);
  expectNothingDrawn("path visible");
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100) << "the arrows are in view";
}

TEST_F(OffViewTest, TheLitAreaFollowsTheLensDistortion)
{
  // The same lens with k1 = 0.5 on the cue's own topic (the ProjectorCamera keeps the ideal one):
  // a pixel's ray is undistortPoints of it, so the lit area's corners come in and its edges bulge.
  sensor_msgs::CameraInfo distorted = info_;
  distorted.distortion_model = "plumb_bob";
  distorted.D = {0.5, 0.0, 0.0, 0.0, 0.0};
  ASSERT_TRUE(pathWithCue(kLeftwards, M_PI / 2, kOwnInfo));
  ros::Publisher info = nh_.advertise<sensor_msgs::CameraInfo>(kOwnInfo, 1, true);
  const Vec2 target{kRobotX, 1.5};
  // FloorFootprint's outline: 8 rays per image edge, evenly in pixels (floor_footprint.h).
  const Vec2 tip = nearestOn(inset(litArea(distorted, 8), kMargin), target);
  const Vec2 ideal_tip = nearestOn(inset(litArea(), kMargin), target);
  std::printf("edge arrow's tip: %.4f %.4f through the distortion, %.4f %.4f without\n", tip.x, tip.y, ideal_tip.x,
              ideal_tip.y);
  ASSERT_GT(std::hypot(tip.x - ideal_tip.x, tip.y - ideal_tip.y), 0.05) << "the distortion must move the arrow";
  const Vec2 direction{0.0, 1.0};
  // First the ideal lens, then (robot and path standing) the distorting one: the arrow follows.
  info.publish(info_);
  QImage frame = grabUntil([&](const QImage& image) { return cyanAt(image, add(ideal_tip, direction, -0.15)); });
  expectArrow(frame, ideal_tip, direction);
  info.publish(distorted);
  frame = grabUntil([&](const QImage& image) { return blackAt(image, add(ideal_tip, direction, -0.04)); });
  expectArrow(frame, tip, direction);
  EXPECT_TRUE(statusSays("edge arrow")) << status();
}

TEST_F(OffViewTest, TurnInPlaceShowsTheGlyphOnTheLitAreaTurningTheRightWay)
{
  // The robot faces +x, its path leaves to the right (-y): it turns right on the spot first.
  ASSERT_TRUE(pathWithCue(polyline({{kRobotX, 0.0}, {kRobotX, -2.5}}), 0.0));
  const Vec2 centre = centroidOf(litArea());
  // The glyph (turn_signal.h): a quarter-circle band of radius 0.5 size and width size / 5 whose
  // head (0.45 size long, 0.22 size wide) points towards the turn; size 0.3, its box
  // (0 .. 0.216 forwards, -0.03 .. 0.285 towards the turn) centred on the lit area's centroid. In
  // that box the head's middle is 0.15 forwards, 0.19 towards the turn: from the centre +0.042,
  // +0.0625. Mirrored to the other side (+0.042, -0.13) lies outside the band.
  const Vec2 forward{1.0, 0.0}, toward{0.0, -1.0};
  const Vec2 head = add(add(centre, forward, 0.042), toward, 0.0625);
  const Vec2 other_side = add(add(centre, forward, 0.042), toward, -0.13);
  const QImage frame = grabUntil([&](const QImage& image) { return cyanAt(image, head); });
  saveShot(frame, "cues-off-view-turn");
  EXPECT_TRUE(cyanAt(frame, head)) << describe(colourAt(frame, head));
  EXPECT_TRUE(blackAt(frame, other_side)) << "a right turn's head is not on the left: "
                                          << describe(colourAt(frame, other_side));
  EXPECT_GT(cyanPixels(frame), 300);
  EXPECT_TRUE(statusSays("turn in place, right")) << status();

  // Turning left instead: the head moves to the other side.
  publishPath(polyline({{kRobotX, 0.0}, {kRobotX, 2.5}}));
  const QImage left = grabUntil([&](const QImage& image) { return cyanAt(image, other_side); });
  EXPECT_TRUE(cyanAt(left, add(add(centre, forward, 0.042), toward, -0.0625)));
  EXPECT_TRUE(blackAt(left, add(add(centre, forward, 0.042), toward, 0.13)));
  EXPECT_TRUE(statusSays("turn in place, left")) << status();
}

TEST_F(OffViewTest, FinalApproachPointsAtTheDestinationOutsideTheLitArea)
{
  // 0.15 m ahead, then 0.75 m to the right: 0.9 m left (Final approach 1 m), all outside the lit area.
  const Vec2 destination{0.45, -0.75};
  ASSERT_TRUE(pathWithCue(polyline({{kRobotX, 0.0}, {0.45, 0.0}, destination}), 0.0));
  const Vec2 tip = nearestOn(inset(litArea(), kMargin), destination);
  const Vec2 direction = unit(Vec2{destination.x - tip.x, destination.y - tip.y});
  const QImage frame = grabUntil([&](const QImage& image) { return cyanAt(image, add(tip, direction, -0.15)); });
  saveShot(frame, "cues-off-view-destination");
  expectArrow(frame, tip, direction);
  EXPECT_TRUE(statusSays("destination 0.9 m away")) << status();
}

TEST_F(OffViewTest, HysteresisKeepsACueUntilFortyPercentAreVisible)
{
  // Look-ahead 2 m. "Mid": 0.2 m ahead, then to the right along x 0.5 (the lit area's near edge is
  // at x ~0.469, 0.615 m wide there): ~0.65 of 2 m in view, ~0.32: between 0.25 and 0.4.
  // "Gone": to the right along x 0.4, none of it in view (and 0.4 m longer, to tell them apart).
  const std::vector<Vec2> mid = polyline({{kRobotX, 0.0}, {0.5, 0.0}, {0.5, -3.0}});
  const std::vector<Vec2> gone = polyline({{kRobotX, 0.0}, {0.4, 0.0}, {0.4, -3.5}});
  ASSERT_TRUE(pathWithCue(mid, 0.0));
  cue()->subProp("Look-ahead")->setValue(2.0);
  expectNothingDrawn("path visible");  // a third in view: no cue appears
  publishPath(gone);
  EXPECT_TRUE(statusSays("edge arrow")) << status();
  EXPECT_GT(cyanPixels(grabUntil([&](const QImage& image) { return cyanPixels(image) > 100; })), 100);
  publishPath(mid);  // a third in view again: the cue stays
  EXPECT_TRUE(waitFor([&] { return path_->spacedPath().path_length < 3.3; }));
  spinFor(0.3);
  EXPECT_TRUE(statusSays("edge arrow")) << status();
  EXPECT_GT(cyanPixels(grabUntil([&](const QImage& image) { return cyanPixels(image) > 100; })), 100);
  publishPath(kAhead);
  expectNothingDrawn("path visible");
}

TEST_F(OffViewTest, KeepsOffTheArrowsThatAreDrawnOnly)
{
  // The path comes down x 0.62 from y 0.5 (through where the edge arrow's shaft would be), to the
  // robot at (0.3, 0), then leaves to the left as kLeftwards. With the Horizon on, the part behind
  // the robot is not drawn and the cue sits where the oracle says; with it off that part is drawn
  // and the cue must keep off it.
  const Vec2 tip = nearestOn(inset(litArea(), kMargin), Vec2{kRobotX, 1.5});
  std::vector<Vec2> points = polyline({{tip.x, 0.5}, {tip.x, 0.15}, {kRobotX, 0.0}, {kRobotX, 2.5}});
  ASSERT_TRUE(pathWithCue(points, M_PI / 2));
  path_->subProp("Horizon")->setValue(true);
  const Vec2 direction{0.0, 1.0};
  QImage frame = grabUntil([&](const QImage& image) { return cyanAt(image, add(tip, direction, -0.15)); });
  expectArrow(frame, tip, direction);
  EXPECT_EQ(countColour(frame, kArrowMagenta), 0) << "no arrow drawn behind the robot";

  path_->subProp("Horizon")->setValue(false);
  frame = grabUntil([&](const QImage& image) {
    return countColour(image, kArrowMagenta) > 50 && !cyanAt(image, add(tip, direction, -0.15));
  });
  saveShot(frame, "cues-off-view-clear");
  EXPECT_GT(countColour(frame, kArrowMagenta), 50) << "the arrows behind the robot are drawn";
  EXPECT_GT(cyanPixels(frame), 100) << "the cue moved, it did not go: " << status();
  for (double y = 0.17; y < 0.49; y += 0.02)
  {
    EXPECT_FALSE(cyanAt(frame, Vec2{tip.x, y})) << "the cue on the drawn path at y " << y;
  }
}

TEST_F(OffViewTest, BadInputSaysWhyAndDrawsNothing)
{
  ASSERT_TRUE(pathWithCue(kLeftwards, M_PI / 2, kOwnInfo));
  ros::Publisher info = nh_.advertise<sensor_msgs::CameraInfo>(kOwnInfo, 1, true);
  expectNothingDrawn("No CameraInfo received yet");
  EXPECT_EQ(statusOf(path_, "Off-view cue").level, rviz::StatusProperty::Warn);

  sensor_msgs::CameraInfo zeros;
  zeros.header.frame_id = kOpticalFrame;
  info.publish(zeros);
  expectNothingDrawn("Unusable CameraInfo");
  EXPECT_EQ(statusOf(path_, "Off-view cue").level, rviz::StatusProperty::Error);

  sensor_msgs::CameraInfo nan = info_;
  nan.K[0] = nan.P[0] = std::numeric_limits<double>::quiet_NaN();
  info.publish(nan);
  EXPECT_TRUE(waitFor([&] { return path_->offViewSource().messages() >= 2; }));
  expectNothingDrawn("Unusable CameraInfo");

  sensor_msgs::CameraInfo elsewhere = info_;
  elsewhere.header.frame_id = "no_such_projector";
  info.publish(elsewhere);
  expectNothingDrawn("No transform from the projector's frame 'no_such_projector'");
  EXPECT_EQ(statusOf(path_, "Off-view cue").level, rviz::StatusProperty::Error);

  // The same lens in the right frame: the cue appears (the input above was all that was missing).
  info.publish(info_);
  EXPECT_TRUE(statusSays("edge arrow")) << status();
  EXPECT_GT(cyanPixels(grabUntil([&](const QImage& image) { return cyanPixels(image) > 100; })), 100);

  // No robot: nothing.
  path_->subProp("Robot frame")->setValue("no_such_robot");
  expectNothingDrawn("No robot pose");
  EXPECT_TRUE(path_->isEnabled());

  // The group off: no status, nothing drawn.
  path_->subProp("Robot frame")->setValue("base_link");
  EXPECT_TRUE(statusSays("edge arrow")) << status();
  cue()->setValue(false);
  EXPECT_TRUE(waitFor([&] { return !statusOf(path_, "Off-view cue").present; }));
  const auto none = [&](const QImage& image) { return cyanPixels(image) == 0; };
  EXPECT_EQ(cyanPixels(grabUntil(none)), 0);
}

TEST_F(OffViewTest, ARvizResetKeepsTheLensOfALatchedCameraInfo)
{
  // The CameraInfo is published once, latched (projector_info_publisher does): after rviz's Reset
  // (also at every backward jump of ROS time) it is not sent again, and the cue must come back.
  ASSERT_TRUE(pathWithCue(kLeftwards, M_PI / 2, kOwnInfo));
  ros::Publisher info = nh_.advertise<sensor_msgs::CameraInfo>(kOwnInfo, 1, true);
  info.publish(info_);
  EXPECT_TRUE(statusSays("edge arrow")) << status();
  const std::size_t messages = path_->offViewSource().messages();
  path_->reset();
  EXPECT_TRUE(waitFor([&] { return path_->offViewTriangleCount() == 0 || !statusOf(path_, "Off-view cue").present ||
                                   statusOf(path_, "Path").text.contains("No path"); }));
  EXPECT_TRUE(waitFor([&] { return path_->offViewTriangleCount() > 0; }, 8.0)) << status();
  EXPECT_TRUE(statusSays("edge arrow")) << status();
  EXPECT_EQ(path_->offViewSource().messages(), messages) << "no new CameraInfo was needed";
  EXPECT_GT(cyanPixels(grabUntil([&](const QImage& image) { return cyanPixels(image) > 100; })), 100);
}

namespace
{
class OffViewConfigTest : public RvizTest
{
};
}  // namespace

TEST_F(OffViewConfigTest, PropertiesAreSavedAndLoaded)
{
  const std::map<std::string, QVariant> values = {{"Projector info topic", "/projector/camera_info"},
                                                  {"Look-ahead", 2.5},
                                                  {"Final approach", 0.7},
                                                  {"Arrow size", 0.4},
                                                  {"Color", QColor(10, 20, 30)},
                                                  {"Alpha", 0.6}};
  std::map<std::string, std::string> shown = expectGroupSavedAndLoaded("Off-view cue", values);
  EXPECT_EQ(shown["Projector info topic"], "/projector/camera_info");
}

TEST_F(OffViewConfigTest, AConfigWithoutTheGroupLoadsWithItOffAndBadValuesAreReported)
{
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readString(config, R"(
Displays:
  - Class: rviz_projector/ProjectedPath
    Name: Saved before the off-view cue existed
    Enabled: true
    Topic: /test/plan
  - Class: rviz_projector/ProjectedPath
    Name: Bad off-view cue
    Enabled: true
    Topic: /test/plan
    Off-view cue:
      Value: true
      Look-ahead: -3
      Arrow size: abc
)");
  ASSERT_FALSE(reader.error());
  rviz_->manager()->load(config);
  rviz::DisplayGroup* root = rviz_->manager()->getRootDisplayGroup();
  ASSERT_EQ(root->numDisplays(), 2);
  rviz::Display* old = root->getDisplayAt(0);
  EXPECT_FALSE(old->subProp("Off-view cue")->getValue().toBool());
  EXPECT_NEAR(old->subProp("Off-view cue")->subProp("Look-ahead")->getValue().toDouble(), 1.5, 1e-6);
  spinFor(0.2);  // statuses settle (the absence of a status is the verdict)
  EXPECT_FALSE(statusOf(old, "Off-view cue").present);
  EXPECT_FALSE(statusOf(old, "Config").present) << statusOf(old, "Config").text.toStdString();

  rviz::Display* bad = root->getDisplayAt(1);
  EXPECT_GT(bad->subProp("Off-view cue")->subProp("Look-ahead")->getValue().toDouble(), 0.0);
  const Status s = statusOf(bad, "Config");
  ASSERT_TRUE(s.present);
  for (const char* name : {"Look-ahead: '-3'", "Arrow size: 'abc'"})
  {
    EXPECT_NE(s.text.indexOf(name), -1) << name << " missing in: " << s.text.toStdString();
  }
}
