// ProjectedPath's legibility cues (issue 15) in a real rviz, judged on the projector output's
// pixels: horizon cut and fade, marching arrows at two ROS times, goal-state colours, the
// pre-motion warning's blinking, the turn-signal glyph. ROS time is simulated (ros::Time::setNow):
// between two steps of a test nothing moves. Expected places come from the spacing rule by hand
// (tips at r + gap + phase + k * spacing back from the destination: 0.1 + 0.05 + ... with the
// defaults) and image_geometry (windowPixel), never from the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include <actionlib_msgs/GoalStatusArray.h>
#include <rviz/display.h>
#include <rviz/properties/property.h>

#include "projector_test_fixture.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"

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

constexpr double kStart = 0.3, kEnd = 2.5;  // the test path: straight along +x at y = 0
constexpr double kFirstTip = 0.15;           // circle radius 0.1 + gap 0.05
constexpr double kSpacing = 0.25, kArrow = 0.18;
const QRgb kRed = qRgb(255, 0, 0), kWhite = qRgb(255, 255, 255), kGreen = qRgb(0, 255, 0);

std::vector<Vec2> straightPath(double end = kEnd)
{
  std::vector<Vec2> points;
  for (double x = kStart; x < end - 1e-9; x += 0.05)
  {
    points.push_back({x, 0.0});
  }
  points.push_back({end, 0.0});
  return points;
}

/// Hand-computed tips (x) of the static arrows of straightPath(end) with phase `phase`.
std::vector<double> tipsX(double phase, double end = kEnd)
{
  std::vector<double> tips;
  for (int k = 0;; ++k)
  {
    const double from_end = kFirstTip + phase + kSpacing * k;
    if (from_end + kArrow > end - kStart + 1e-9)
    {
      return tips;
    }
    tips.push_back(end - from_end);
  }
}

class PathCuesTest : public ProjectorSceneTest
{
protected:
  void SetUp() override
  {
    ProjectorSceneTest::SetUp();
    // An even whole second: 1.5 Hz blinking (from time 0) is then lit in [0, 1/3) s after it.
    start_ = ros::Time(2.0 * std::floor(ros::WallTime::now().toSec() / 2.0));
    ros::Time::setNow(start_);
  }

  void at(double t) { ros::Time::setNow(start_ + ros::Duration(t)); }

  /// Colour of the floor point's pixel in the projector output (letterbox removed).
  QRgb colourAt(const QImage& frame, const Vec2& floor) const
  {
    const Vec2 px = windowPixel(floor);
    return frame.pixel(int(std::lround(px.x)), int(std::lround(px.y)));
  }

  /// The output once `ok` holds (or after the timeout: the test then fails on its checks).
  QImage grabUntil(const std::function<bool(const QImage&)>& ok) { return imagePart(grabWhen(ok, 8.0)); }

  rviz::Property* cue(const char* name) { return path_->subProp(name); }

  /// Whether a floor point is inside the projector's image (2 pixels in from its edges).
  bool inView(const Vec2& floor) const
  {
    const Vec2 px = windowPixel(floor);
    const int w = projector_->outputWindow()->width(), h = projector_->outputWindow()->height();
    return px.x >= 2 && px.y >= 2 && px.x <= w - 3 && px.y <= h - 3;
  }

  void publishStatus(const std::string& id, std::uint8_t status)
  {
    actionlib_msgs::GoalStatusArray msg;
    msg.header.stamp = ros::Time::now();
    msg.status_list.resize(1);
    msg.status_list[0].goal_id.id = id;
    msg.status_list[0].goal_id.stamp = start_;
    msg.status_list[0].status = status;
    status_pub_.publish(msg);
  }

  void useStateTopic()
  {
    status_pub_ = nh_.advertise<actionlib_msgs::GoalStatusArray>("/test/status", 5, true);
    cue("State topic")->setValue("/test/status");
  }

  ros::Time start_;
  rviz_projector::ProjectedPathDisplay* path_ = nullptr;
  ros::Publisher status_pub_;
};

}  // namespace

TEST_F(PathCuesTest, HorizonCutsAndFadesByTheTipsArcLength)
{
  publishStaticTransform("map", "base_link", 0.9, 0.1, 0.0, 0.0);  // nearest path point x = 0.9: arc 0.6
  path_ = addPath("/test/plan", straightPath());
  ASSERT_NE(path_, nullptr);
  cue("Horizon")->subProp("Length")->setValue(1.0);
  cue("Horizon")->subProp("Fade")->setValue(0.5);
  cue("Horizon")->setValue(true);
  // Window: arc [0.6, 1.6] = x [0.9, 1.9], fading from x = 1.4. Tips 0.85 (behind), 1.10, 1.35 (full),
  // 1.60 (alpha (1.9 - 1.6) / 0.5 = 0.6), 1.85 (0.1), 2.10 and 2.35 (beyond), destination 2.5 (beyond).
  const QImage frame = grabUntil([&](const QImage& image) {
    return !path_->spacedPath().arrows.empty() && sameColour(colourAt(image, {1.60 - 0.13, 0.0}), qRgb(153, 0, 153), 20) &&
           countColour(image, kGreen, 40) == 0;
  });
  const struct
  {
    double tip;
    double alpha;
  } expected[] = {{0.85, 0.0}, {1.10, 1.0}, {1.35, 1.0}, {1.60, 0.6}, {1.85, 0.1}, {2.10, 0.0}, {2.35, 0.0}};
  saveShot(frame, "cues-horizon");
  int checked = 0;
  for (const auto& e : expected)
  {
    // On the shaft, 0.13 m behind the tip (the shaft is 0.1 m long behind the 0.08 m head).
    if (!inView({e.tip - 0.13, 0.0}))
    {
      continue;  // beyond the lit area
    }
    ++checked;
    const QRgb c = colourAt(frame, {e.tip - 0.13, 0.0});
    const int want = int(std::lround(255 * e.alpha));
    EXPECT_NEAR(qRed(c), want, 20) << "arrow with tip at x = " << e.tip;
    EXPECT_NEAR(qBlue(c), want, 20) << "arrow with tip at x = " << e.tip;
    EXPECT_LE(qGreen(c), 20);
  }
  EXPECT_GE(checked, 5) << "tips 0.85 .. 1.85 are in view";
  // Off again: every arrow at full colour.
  cue("Horizon")->setValue(false);
  const QImage all = grabUntil([&](const QImage& image) {
    return sameColour(colourAt(image, {1.85 - 0.13, 0.0}), kArrowMagenta, 30);
  });
  EXPECT_TRUE(sameColour(colourAt(all, {1.85 - 0.13, 0.0}), kArrowMagenta, 30));
  EXPECT_TRUE(sameColour(colourAt(all, {0.85 - 0.13, 0.0}), kArrowMagenta, 30));
}

TEST_F(PathCuesTest, MarchingArrowsSitWhereTheTimeSaysAndReplansChangeNothing)
{
  path_ = addPath("/test/plan", straightPath());
  ASSERT_NE(path_, nullptr);
  cue("Marching")->subProp("Speed")->setValue(0.1);
  cue("Marching")->setValue(true);
  // At each time, the phase by hand: (-0.1 t) mod 0.25 with t the absolute ROS time in seconds.
  for (double t : {0.2, 0.9})
  {
    at(t);
    const double now = (start_ + ros::Duration(t)).toSec();
    double phase = std::fmod(-0.1 * now, kSpacing);
    phase = phase < 0 ? phase + kSpacing : phase;
    const std::vector<double> tips = tipsX(phase);
    ASSERT_GE(tips.size(), 4u);
    const QImage frame = grabUntil([&](const QImage& image) {
      for (double tip : tips)
      {
        const Vec2 shaft{tip - 0.13, 0.0};
        if (inView(shaft) && !sameColour(colourAt(image, shaft), kArrowMagenta, 30))
        {
          return false;
        }
      }
      return true;
    });
    int checked = 0;
    for (double tip : tips)
    {
      const Vec2 shaft{tip - 0.13, 0.0}, ahead{tip + 0.02, 0.0};
      if (!inView(shaft) || !inView(ahead))
      {
        continue;
      }
      EXPECT_TRUE(sameColour(colourAt(frame, shaft), kArrowMagenta, 30)) << "t " << t << " tip " << tip;
      EXPECT_TRUE(sameColour(colourAt(frame, ahead), kBlack, 30)) << "t " << t << " 2 cm beyond tip " << tip;
      ++checked;
    }
    EXPECT_GE(checked, 4);
  }
  // A replan of the same route, its first half metre driven: the same arrows at the same time.
  const QImage before = imagePart(grab());
  std::vector<Vec2> trimmed = straightPath();
  trimmed.erase(trimmed.begin(), trimmed.begin() + 10);
  nav_msgs::Path msg;
  msg.header.frame_id = "map";
  for (const Vec2& p : trimmed)
  {
    geometry_msgs::PoseStamped pose;
    pose.header = msg.header;
    pose.pose.position.x = p.x;
    pose.pose.orientation.w = 1;
    msg.poses.push_back(pose);
  }
  const std::size_t builds = path_->meshBuilds();
  path_pub_.publish(msg);
  ASSERT_TRUE(waitFor([&] { return path_->meshBuilds() > builds; }));
  const QImage after = imagePart(grab());
  int differing = 0;
  for (int y = 0; y < after.height(); ++y)
  {
    for (int x = 0; x < after.width(); ++x)
    {
      const Vec2 floor = PixelOracle(info_, kDemoMount).floorPoint({double(x), double(y)});
      if (floor.x > 0.8 + kArrow + 0.02)  // beyond what the trimmed path dropped
      {
        differing += before.pixel(x, y) != after.pixel(x, y) ? 1 : 0;
      }
    }
  }
  EXPECT_EQ(differing, 0) << "a replan of the same route moved arrows";
}

TEST_F(PathCuesTest, StaticArrowsRenderNoFramesAsTimeGoesBy)
{
  path_ = addPath("/test/plan", straightPath());
  ASSERT_NE(path_, nullptr);
  grabWithArrows();
  ASSERT_TRUE(waitForFrames(0));
  const std::uint64_t frames = projector_->framesRendered();
  for (double t = 0.1; t < 1.0; t += 0.1)
  {
    at(t);
    spinFor(0.05);  // a wall-time span: the projector's clock ticks meanwhile (no condition to wait for)
  }
  EXPECT_EQ(projector_->framesRendered(), frames) << "no cue animates: no frame may be rendered";
}

TEST_F(PathCuesTest, GoalStatesColourTheCues)
{
  path_ = addPath("/test/plan", straightPath(1.5));
  ASSERT_NE(path_, nullptr);
  useStateTopic();
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("No goal status received"); }));
  grabWithArrows();  // no message yet: drawn as for an active goal
  publishStatus("g1", actionlib_msgs::GoalStatus::ACTIVE);
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("active"); }));
  const QImage active = grabWithArrows();
  EXPECT_GT(countColour(active, kGreen, 40), 50) << "destination circle in Circle color";

  publishStatus("g1", actionlib_msgs::GoalStatus::ABORTED);
  const QImage failed = grabUntil([&](const QImage& image) { return countColour(image, kArrowMagenta) == 0; });
  saveShot(failed, "cues-failed");
  EXPECT_EQ(countColour(failed, kArrowMagenta), 0) << "a failed goal hides the arrows";
  EXPECT_EQ(countColour(failed, kGreen, 40), 0) << "no circle";
  EXPECT_TRUE(sameColour(colourAt(failed, {1.5, 0.0}), kRed, 30)) << "cross centre in Failed color";
  // Along a diagonal of the cross (0.06 m from the centre): red; on the axis the same distance: floor.
  EXPECT_TRUE(sameColour(colourAt(failed, {1.5 + 0.045, 0.045}), kRed, 40));
  EXPECT_TRUE(sameColour(colourAt(failed, {1.5 + 0.07, 0.0}), kBlack, 40));
  EXPECT_TRUE(statusOf(path_, "State").text.contains("failed"));

  at(1.0);
  publishStatus("g1", actionlib_msgs::GoalStatus::SUCCEEDED);
  const QImage flash = grabUntil([&](const QImage& image) { return countColour(image, kWhite, 40) > 50; });
  EXPECT_TRUE(sameColour(colourAt(flash, {1.5, 0.0}), kWhite, 40)) << "the destination flashes in Succeeded color";
  EXPECT_EQ(countColour(flash, kArrowMagenta), 0);
  at(1.6);  // 0.6 s after the success: cleared
  const QImage cleared = grabUntil([&](const QImage& image) { return countColour(image, kBlack) == image.width() * image.height(); });
  EXPECT_EQ(countColour(cleared, kBlack), cleared.width() * cleared.height());

  // A new goal: everything back. Then no State topic: the goal's state changes nothing.
  publishStatus("g2", actionlib_msgs::GoalStatus::ABORTED);
  grabUntil([&](const QImage& image) { return countColour(image, kRed, 40) > 20; });
  cue("State topic")->setValue("");
  const QImage plain = grabWithArrows();
  EXPECT_GT(countColour(plain, kGreen, 40), 50);
  EXPECT_FALSE(statusOf(path_, "State").present);
}

TEST_F(PathCuesTest, PreMotionWarningBlinksForTheWarningTimeThenSteady)
{
  publishStaticTransform("map", "base_link", 0.3, 0.0, 0.0, 0.0);  // standing still at the start
  path_ = addPath("/test/plan", straightPath(1.5));
  ASSERT_NE(path_, nullptr);
  useStateTopic();
  rviz::Property* warning = cue("State topic")->subProp("Pre-motion warning");
  warning->subProp("Warning time")->setValue(2.0);
  warning->subProp("Blink frequency")->setValue(2.0);
  warning->setValue(true);
  grabWithArrows();
  spinFor(0.2);  // a few frames: the robot's stillness is seen (wall-time span; the sim clock stands)
  publishStatus("go", actionlib_msgs::GoalStatus::ACTIVE);  // becomes active at t = 0
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("active"); }));
  const auto lit = [&](const QImage& image) { return countColour(image, kArrowMagenta) > 100 && countColour(image, kGreen, 40) > 50; };
  const auto dark = [&](const QImage& image) { return countColour(image, kArrowMagenta) == 0 && countColour(image, kGreen, 40) == 0; };
  for (double t : {0.1, 0.35, 0.6, 0.85, 1.6, 1.85})
  {
    at(t);
    const bool on = std::fmod(t * 2.0, 1.0) < 0.5;  // 2 Hz, lit in the first half of each period
    const QImage frame = grabUntil(on ? std::function<bool(const QImage&)>(lit) : std::function<bool(const QImage&)>(dark));
    EXPECT_TRUE(on ? lit(frame) : dark(frame)) << "t = " << t << " should be " << (on ? "lit" : "dark");
  }
  for (double t : {2.1, 2.35, 3.0})
  {
    at(t);
    const QImage frame = grabUntil(lit);
    EXPECT_TRUE(lit(frame)) << "steady after the warning, t = " << t;
  }
}

TEST_F(PathCuesTest, TurnSignalOnTheInsideBeforeASharpTurnOnly)
{
  publishStaticTransform("map", "base_link", 0.3, 0.0, 0.0, 0.0);
  // Straight 1 m from the robot, then left (+y) for 1 m.
  std::vector<Vec2> left;
  for (double x = 0.3; x < 1.3 - 1e-9; x += 0.05)
  {
    left.push_back({x, 0.0});
  }
  for (double y = 0.0; y <= 1.0 + 1e-9; y += 0.05)
  {
    left.push_back({1.3, y});
  }
  path_ = addPath("/test/plan", left);
  ASSERT_NE(path_, nullptr);
  cue("Turn signal")->subProp("Glyph ahead")->setValue(0.8);
  cue("Turn signal")->setValue(true);
  at(0.1);  // 1.5 Hz from time 0: lit while (t mod 2/3) < 1/3; start_ is an even whole second
  // Glyph centre: robot + 0.8 ahead + (0.3 + 0.15) to the left = (1.1, 0.45), 0.3 m across.
  const double now = (start_ + ros::Duration(0.1)).toSec();
  ASSERT_LT(std::fmod(now * 1.5, 1.0), 0.5) << "the test time must fall in a lit half";
  const QImage frame = grabUntil([&](const QImage&) { return path_->glyphTriangleCount() > 0; });
  EXPECT_GT(path_->glyphTriangleCount(), 0u);
  saveShot(frame, "cues-turn");
  int inside = 0, outside = 0;
  for (double dx = -0.15; dx <= 0.15; dx += 0.01)
  {
    for (double dy = -0.15; dy <= 0.15; dy += 0.01)
    {
      inside += sameColour(colourAt(frame, {1.1 + dx, 0.45 + dy}), kArrowMagenta, 30) ? 1 : 0;
      outside += sameColour(colourAt(frame, {1.1 + dx, -0.45 + dy}), kArrowMagenta, 30) ? 1 : 0;
    }
  }
  EXPECT_GT(inside, 40) << "glyph pixels on the left of the path";
  EXPECT_EQ(outside, 0) << "nothing on the right";
  at(0.5);  // dark half: the glyph blinks off
  ASSERT_TRUE(waitFor([&] { return path_->glyphTriangleCount() == 0; }));

  // A straight path: no glyph at any time.
  nav_msgs::Path msg;
  msg.header.frame_id = "map";
  for (const Vec2& p : straightPath())
  {
    geometry_msgs::PoseStamped pose;
    pose.header = msg.header;
    pose.pose.position.x = p.x;
    pose.pose.orientation.w = 1;
    msg.poses.push_back(pose);
  }
  path_pub_.publish(msg);
  ASSERT_TRUE(waitFor([&] { return path_->spacedPath().destination.x > 2.4; }));
  for (double t : {0.1, 0.3})
  {
    at(t);
    spinFor(0.1);
    EXPECT_EQ(path_->glyphTriangleCount(), 0u) << "t = " << t;
  }
}

TEST_F(PathCuesTest, BadInputGetsStatusesAndNothingBreaks)
{
  path_ = addPath("/test/plan", straightPath());
  ASSERT_NE(path_, nullptr);
  cue("Robot frame")->setValue("no_such_frame");
  cue("Horizon")->subProp("Length")->setValue(1.0);
  cue("Horizon")->subProp("Fade")->setValue(0.0);
  cue("Horizon")->setValue(true);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Robot").text.contains("no_such_frame"); }));
  // Without the robot the horizon starts at the path's start: x 0.3 .. 1.3.
  const QImage frame = grabUntil([&](const QImage& image) { return countColour(image, kArrowMagenta) > 50; });
  EXPECT_TRUE(sameColour(colourAt(frame, {0.85 - 0.13, 0.0}), kArrowMagenta, 30));
  EXPECT_TRUE(sameColour(colourAt(frame, {1.85 - 0.13, 0.0}), kBlack, 30));
  useStateTopic();
  actionlib_msgs::GoalStatusArray odd;
  odd.status_list.resize(2);
  odd.status_list[0].status = 42;  // unknown codes are ignored
  odd.status_list[1].status = 200;
  status_pub_.publish(odd);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("No goal in the status list"); }));
  status_pub_.publish(actionlib_msgs::GoalStatusArray());
  spinFor(0.1);
  EXPECT_TRUE(statusOf(path_, "State").present);
  cue("State topic")->setValue("not a valid topic name!");
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").level == rviz::StatusProperty::Error; }));
  cue("Marching")->setValue(true);
  path_->subProp("Spacing mode")->setValue("Paper");
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Marching").present; }));
}
