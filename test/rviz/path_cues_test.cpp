// ProjectedPath's legibility cues (issue 15) in a real rviz, judged on the projector output's
// pixels: horizon cut and fade, marching arrows at two ROS times, no frames for static cues,
// goal-state colours, the pre-motion warning's blinking (not for a goal issued long ago), the
// turn-signal glyph, the Style warning. ROS time is simulated (ros::Time::setNow):
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
constexpr double kStart = 0.3, kEnd = 2.5;  // the test path: straight along +x at y = 0
constexpr double kFirstTip = 0.15;           // circle radius 0.1 + gap 0.05
constexpr double kSpacing = 0.25, kArrow = 0.18;
const QRgb kRed = qRgb(255, 0, 0), kWhite = qRgb(255, 255, 255), kGreen = qRgb(0, 255, 0);

std::vector<Vec2> straightPath(double end = kEnd)
{
  return lineAlongX(kStart, end);
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
    start_ = rviz_projector_test::monotonicTestStart(2.0);
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

  /// One goal's status; `issued` (goal_id.stamp) is start_ unless given.
  void publishStatus(const std::string& id, std::uint8_t status, const ros::Time& issued = ros::Time())
  {
    actionlib_msgs::GoalStatusArray msg;
    msg.header.stamp = ros::Time::now();
    msg.status_list.resize(1);
    msg.status_list[0].goal_id.id = id;
    msg.status_list[0].goal_id.stamp = issued.isZero() ? start_ : issued;
    msg.status_list[0].status = status;
    status_pub_.publish(msg);
  }

  /// A new plan on the path's topic (frame map, poses facing +x).
  void publishPath(const std::vector<Vec2>& points)
  {
    nav_msgs::Path msg;
    msg.header.frame_id = "map";
    for (const Vec2& p : points)
    {
      geometry_msgs::PoseStamped pose;
      pose.header = msg.header;
      pose.pose.position.x = p.x;
      pose.pose.position.y = p.y;
      pose.pose.orientation.w = 1;
      msg.poses.push_back(pose);
    }
    path_pub_.publish(msg);
  }

  void useStateTopic()
  {
    status_pub_ = nh_.advertise<actionlib_msgs::GoalStatusArray>("/test/status", 5, true);
    cue("State topic")->setValue("/test/status");
  }

  /// The robot stands still at x 0.3 on a 1.5 m path; State topic set; pre-motion warning on
  /// (2 s at 2 Hz). False when the path display could not be added.
  bool standingRobotWithWarning()
  {
    publishStaticTransform("map", "base_link", 0.3, 0.0, 0.0, 0.0);
    path_ = addPath("/test/plan", straightPath(1.5));
    if (path_ == nullptr)
    {
      return false;
    }
    useStateTopic();
    rviz::Property* warning = cue("State topic")->subProp("Pre-motion warning");
    warning->subProp("Warning time")->setValue(2.0);
    warning->subProp("Blink frequency")->setValue(2.0);
    warning->setValue(true);
    return true;
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
  // The destination, on a path ending in view at x = 1.5 (arc 1.2; the robot at arc 0.6). Horizon
  // 1.0: window arc [0.6, 1.6] fading from 1.1, so the circle has alpha (1.6 - 1.2) / 0.5 = 0.8.
  publishPath(straightPath(1.5));
  ASSERT_TRUE(waitFor([&] { return std::abs(path_->spacedPath().destination.x - 1.5) < 1e-6; }));
  const QImage near = grabUntil([&](const QImage& image) { return sameColour(colourAt(image, {1.5, 0.0}), qRgb(0, 204, 0), 20); });
  const QRgb centre = colourAt(near, {1.5, 0.0});
  EXPECT_NEAR(qGreen(centre), 204, 20) << "destination within the horizon, alpha 0.8";
  EXPECT_LE(qRed(centre) + qBlue(centre), 20);
  // Horizon 0.5: window arc [0.6, 1.1]; the destination (arc 1.2) is beyond it: not drawn.
  cue("Horizon")->subProp("Length")->setValue(0.5);
  // The circle's own pixel in the condition: kGreen counts full green only, which the alpha-0.8
  // circle of the frame before is not.
  const QImage cut = grabUntil([&](const QImage& image) {
    return countColour(image, kGreen, 40) == 0 && sameColour(colourAt(image, {1.5, 0.0}), kBlack, 20);
  });
  EXPECT_EQ(countColour(cut, kGreen, 40), 0) << "destination beyond the horizon: hidden";
  EXPECT_TRUE(sameColour(colourAt(cut, {1.5, 0.0}), kBlack, 20));
  publishPath(straightPath());
  ASSERT_TRUE(waitFor([&] { return path_->spacedPath().destination.x > 2.4; }));
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
    // Both checks in the condition: the frame of the previous time has its arrows' heads on these
    // shafts (tips 0.07 m behind), so shafts alone would accept it before this time's frame shows.
    const QImage frame = grabUntil([&](const QImage& image) {
      for (double tip : tips)
      {
        const Vec2 shaft{tip - 0.13, 0.0}, ahead{tip + 0.02, 0.0};
        if (inView(shaft) && inView(ahead) &&
            (!sameColour(colourAt(image, shaft), kArrowMagenta, 30) || !sameColour(colourAt(image, ahead), kBlack, 30)))
        {
          return false;
        }
      }
      return true;
    });
    saveShot(frame, t < 0.5 ? "cues-marching-1" : "cues-marching-2");
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
  const std::size_t builds = path_->meshBuilds();
  publishPath(trimmed);
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
  publishStaticTransform("map", "base_link", 0.9, 0.0, 0.0, 0.0);  // standing still on the path
  path_ = addPath("/test/plan", straightPath());
  ASSERT_NE(path_, nullptr);
  // Frames rendered (by the projector's own clock) while ROS time runs from `from` to `to`.
  const auto framesWhileTimeRuns = [&](double from, double to) {
    const std::uint64_t before = projector_->framesRendered();
    for (double t = from; t < to - 1e-9; t += 0.1)
    {
      at(t);
      spinFor(0.05);  // a wall-time span: the projector's clock ticks meanwhile (no condition to wait for)
    }
    return projector_->framesRendered() - before;
  };
  grabWithArrows();
  EXPECT_EQ(framesWhileTimeRuns(0.1, 1.0), 0u) << "no cue on: no frame may be rendered";

  // Cues on that stand still in steady state: the horizon (the robot does not move) and an active
  // goal's colours (no warning).
  cue("Horizon")->subProp("Length")->setValue(1.0);
  cue("Horizon")->subProp("Fade")->setValue(0.0);
  cue("Horizon")->setValue(true);
  useStateTopic();
  publishStatus("g1", actionlib_msgs::GoalStatus::ACTIVE);
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("active"); }));
  // Horizon from x 0.9: the arrow with its tip at 0.85 is gone, the one at 1.10 drawn.
  const QImage steady = grabUntil([&](const QImage& image) {
    return sameColour(colourAt(image, {0.85 - 0.13, 0.0}), kBlack, 20) &&
           sameColour(colourAt(image, {1.10 - 0.13, 0.0}), kArrowMagenta, 30);
  });
  ASSERT_TRUE(sameColour(colourAt(steady, {0.85 - 0.13, 0.0}), kBlack, 20)) << "the horizon applies";
  ASSERT_TRUE(sameColour(colourAt(steady, {1.10 - 0.13, 0.0}), kArrowMagenta, 30));
  spinFor(0.2);  // lets any frame the set-up asked for go out (not a verdict)
  EXPECT_EQ(framesWhileTimeRuns(1.1, 2.0), 0u) << "static cues on: no frame may be rendered";

  // The counter can count: marching arrows move with ROS time and need frames.
  cue("Marching")->setValue(true);
  EXPECT_GT(framesWhileTimeRuns(2.1, 3.0), 3u) << "marching must render frames as time goes by";
}

TEST_F(PathCuesTest, GoalStatesColourTheCues)
{
  path_ = addPath("/test/plan", straightPath(1.5));
  ASSERT_NE(path_, nullptr);
  // Path x 0.3 .. 1.5: tips 0.15, 0.40, 0.65, 0.90 back from the destination (1.15 + 0.18 > 1.2).
  const std::vector<double> tips = tipsX(0.0, 1.5);
  ASSERT_EQ(tips.size(), 4u);
  // Everything as for an active goal: each arrow's shaft in Arrow color, the circle in Circle color.
  const auto drawnAsActive = [&](const QImage& image) {
    for (double tip : tips)
    {
      if (inView({tip - 0.13, 0.0}) && !sameColour(colourAt(image, {tip - 0.13, 0.0}), kArrowMagenta, 30))
      {
        return false;
      }
    }
    return sameColour(colourAt(image, {1.5, 0.0}), kGreen, 40);
  };
  // Failed: no arrow, no circle; a cross in Failed color. Along a diagonal of the cross (0.06 m
  // from the centre): red; on the axis the same distance: floor.
  const auto crossed = [&](const QImage& image) {
    return countColour(image, kArrowMagenta, 40) == 0 && countColour(image, kGreen, 40) == 0 &&
           sameColour(colourAt(image, {1.5, 0.0}), kRed, 30) && sameColour(colourAt(image, {1.5 + 0.045, 0.045}), kRed, 40) &&
           sameColour(colourAt(image, {1.5 + 0.07, 0.0}), kBlack, 40);
  };
  useStateTopic();
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("No goal status received"); }));
  EXPECT_TRUE(drawnAsActive(grabUntil(drawnAsActive))) << "no message yet: drawn as for an active goal";
  publishStatus("g1", actionlib_msgs::GoalStatus::ACTIVE);
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("'g1': active"); }));
  const QImage active = grabUntil(drawnAsActive);
  EXPECT_TRUE(drawnAsActive(active)) << "active: arrows in Arrow color, circle in Circle color";
  EXPECT_GT(countColour(active, kGreen, 40), 50) << "destination circle in Circle color";

  publishStatus("g1", actionlib_msgs::GoalStatus::ABORTED);
  const QImage failed = grabUntil(crossed);
  saveShot(failed, "cues-failed");
  EXPECT_TRUE(crossed(failed)) << "aborted: arrows hidden, red cross";
  EXPECT_TRUE(statusOf(path_, "State").text.contains("failed"));

  at(1.0);
  publishStatus("g1", actionlib_msgs::GoalStatus::SUCCEEDED);
  const QImage flash = grabUntil([&](const QImage& image) { return countColour(image, kWhite, 40) > 50; });
  EXPECT_TRUE(sameColour(colourAt(flash, {1.5, 0.0}), kWhite, 40)) << "the destination flashes in Succeeded color";
  saveShot(flash, "cues-succeeded");
  EXPECT_EQ(countColour(flash, kArrowMagenta), 0);
  at(1.6);  // 0.6 s after the success: cleared
  const QImage cleared = grabUntil([&](const QImage& image) { return countColour(image, kBlack) == image.width() * image.height(); });
  EXPECT_EQ(countColour(cleared, kBlack), cleared.width() * cleared.height());

  // A new goal: arrows and the green circle back.
  publishStatus("g2", actionlib_msgs::GoalStatus::ACTIVE);
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("'g2': active"); }));
  EXPECT_TRUE(drawnAsActive(grabUntil(drawnAsActive))) << "a new active goal after a success: everything back";
  // Preempted counts as failed.
  publishStatus("g2", actionlib_msgs::GoalStatus::PREEMPTED);
  EXPECT_TRUE(crossed(grabUntil(crossed))) << "preempted: arrows hidden, red cross";
  EXPECT_TRUE(statusOf(path_, "State").text.contains("'g2': failed"));

  // No State topic: the goal's state changes nothing.
  cue("State topic")->setValue("");
  EXPECT_TRUE(drawnAsActive(grabUntil(drawnAsActive))) << "without a State topic: drawn as for an active goal";
  EXPECT_FALSE(statusOf(path_, "State").present);
}

TEST_F(PathCuesTest, PreMotionWarningBlinksForTheWarningTimeThenSteady)
{
  ASSERT_TRUE(standingRobotWithWarning());
  cue("Horizon")->setValue(true);  // from the robot on: shows where the display sees the robot
  grabWithArrows();
  spinFor(0.2);  // a few frames: the robot's stillness is seen (wall-time span; the sim clock stands)
  publishStatus("go", actionlib_msgs::GoalStatus::ACTIVE);  // becomes active at t = 0
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("active"); }));
  const auto lit = [&](const QImage& image) { return countColour(image, kArrowMagenta) > 100 && countColour(image, kGreen, 40) > 50; };
  const auto dark = [&](const QImage& image) { return countColour(image, kArrowMagenta) == 0 && countColour(image, kGreen, 40) == 0; };
  for (double t : {0.1, 0.35, 0.6, 0.85, 1.6, 1.85})
  {
    at(t);
    if (t == 0.6)
    {
      // The robot starts moving (0.6 m ahead: the horizon drops the arrow with its tip at 0.85, the one
      // at 1.10 stays) and the status repeats, as move_base's does: the started warning runs on.
      // The display reads tf when the clock moves on: it ticks forward in ms steps (still lit).
      publishStaticTransform("map", "base_link", 0.9, 0.0, 0.0, 0.0);
      double tick = t;
      const QImage moved = grabUntil([&](const QImage& image) {
        tick = std::min(tick + 0.001, 0.7);
        at(tick);
        return sameColour(colourAt(image, {0.85 - 0.13, 0.0}), kBlack, 20) &&
               sameColour(colourAt(image, {1.10 - 0.13, 0.0}), kArrowMagenta, 30);
      });
      ASSERT_TRUE(sameColour(colourAt(moved, {0.85 - 0.13, 0.0}), kBlack, 20)) << "the display sees the robot move";
      publishStatus("go", actionlib_msgs::GoalStatus::ACTIVE);
      spinFor(0.1);  // the repeated status is taken (it changes no status text to wait for)
    }
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

TEST_F(PathCuesTest, AGoalIssuedLongAgoDoesNotWarnAFreshOneDoes)
{
  ASSERT_TRUE(standingRobotWithWarning());
  grabWithArrows();
  spinFor(0.2);  // a few frames: the robot's stillness is seen (wall-time span; the sim clock stands)
  const auto lit = [&](const QImage& image) { return countColour(image, kArrowMagenta) > 100 && countColour(image, kGreen, 40) > 50; };
  const auto dark = [&](const QImage& image) { return countColour(image, kArrowMagenta) == 0 && countColour(image, kGreen, 40) == 0; };
  // Issued 10 s ago (rviz started while the robot was on its way), seen active at t = 0: no warning,
  // so lit at the times a 2 Hz warning would be dark (0.35, 0.85: second half of a period).
  publishStatus("old", actionlib_msgs::GoalStatus::ACTIVE, start_ - ros::Duration(10.0));
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("'old': active"); }));
  for (double t : {0.35, 0.85})
  {
    at(t);
    EXPECT_TRUE(lit(grabUntil(lit))) << "an old goal does not blink, t = " << t;
  }
  // A fresh goal at t = 3 (issued now): it blinks, dark 0.35 s after.
  at(3.0);
  publishStatus("fresh", actionlib_msgs::GoalStatus::ACTIVE, start_ + ros::Duration(3.0));
  ASSERT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("'fresh': active"); }));
  at(3.35);
  EXPECT_TRUE(dark(grabUntil(dark))) << "a fresh goal blinks";
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
  // Glyph centre: robot + 0.8 ahead + (0.3 + 0.15) to the left = (1.1, 0.45), 0.3 m across (its
  // shape spans 0.22 m along x). Arrow colour pixels in x 1.1 +- 0.12, y 0.45 +- 0.15 (side +1) or
  // its mirror on the right (side -1): no arrow reaches there (the heads on x = 1.3 end at 1.24).
  const auto glyphPixels = [&](const QImage& image, double side) {
    int n = 0;
    for (int i = -12; i <= 12; ++i)
    {
      for (int j = -15; j <= 15; ++j)
      {
        n += sameColour(colourAt(image, {1.1 + 0.01 * i, side * 0.45 + 0.01 * j}), kArrowMagenta, 30) ? 1 : 0;
      }
    }
    return n;
  };
  // 1.5 Hz from time 0: lit while frac(1.5 t) < 0.5; start_ is an even whole second.
  const auto litPhase = [&](double t) { return std::fmod((start_ + ros::Duration(t)).toSec() * 1.5, 1.0) < 0.5; };
  at(0.1);
  ASSERT_TRUE(litPhase(0.1)) << "the test time must fall in a lit half";
  const QImage frame = grabUntil([&](const QImage& image) { return glyphPixels(image, 1.0) > 40; });
  saveShot(frame, "cues-turn");
  EXPECT_GT(glyphPixels(frame, 1.0), 40) << "glyph pixels on the left of the path";
  EXPECT_EQ(glyphPixels(frame, -1.0), 0) << "nothing on the right";
  at(0.5);
  ASSERT_FALSE(litPhase(0.5));
  EXPECT_EQ(glyphPixels(grabUntil([&](const QImage& image) { return glyphPixels(image, 1.0) == 0; }), 1.0), 0)
      << "dark half: the glyph blinks off";

  // A straight path at a lit time (0.8: frac(1.2) = 0.2): no glyph on either side. The frame shows
  // the straight path once the arrow with its tip at 1.60 (beyond the turn's corner) is drawn.
  at(0.8);
  ASSERT_TRUE(litPhase(0.8));
  publishPath(straightPath());
  const auto straightShown = [&](const QImage& image) { return sameColour(colourAt(image, {1.60 - 0.13, 0.0}), kArrowMagenta, 30); };
  const QImage straight = grabUntil(straightShown);
  ASSERT_TRUE(straightShown(straight));
  EXPECT_EQ(glyphPixels(straight, 1.0), 0) << "straight path: no glyph on the left";
  EXPECT_EQ(glyphPixels(straight, -1.0), 0) << "straight path: no glyph on the right";
  // The same time with the turn again: the glyph is lit (the check above could see one).
  publishPath(left);
  const QImage turning = grabUntil([&](const QImage& image) { return glyphPixels(image, 1.0) > 40; });
  EXPECT_GT(glyphPixels(turning, 1.0), 40) << "positive control: the turning path at t = 0.8 shows the glyph";
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
  // The cut in the condition too: the frame before the horizon has every arrow.
  const QImage frame = grabUntil([&](const QImage& image) {
    return countColour(image, kArrowMagenta) > 50 && sameColour(colourAt(image, {0.85 - 0.13, 0.0}), kArrowMagenta, 30) &&
           sameColour(colourAt(image, {1.85 - 0.13, 0.0}), kBlack, 30);
  });
  EXPECT_TRUE(sameColour(colourAt(frame, {0.85 - 0.13, 0.0}), kArrowMagenta, 30));
  EXPECT_TRUE(sameColour(colourAt(frame, {1.85 - 0.13, 0.0}), kBlack, 30));
  useStateTopic();
  actionlib_msgs::GoalStatusArray odd;
  odd.status_list.resize(2);
  odd.status_list[0].status = 42;  // unknown codes are ignored
  odd.status_list[1].status = 200;
  status_pub_.publish(odd);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("No goal in the status list"); }));
  // A failed goal, then an empty list: no goal any more, so the arrows are back.
  publishStatus("g9", actionlib_msgs::GoalStatus::ABORTED);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("'g9': failed"); }));
  EXPECT_EQ(countColour(grabUntil([&](const QImage& image) { return countColour(image, kArrowMagenta) == 0; }), kArrowMagenta), 0);
  status_pub_.publish(actionlib_msgs::GoalStatusArray());
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").text.contains("No goal in the status list"); }))
      << "an empty status list: no goal";
  EXPECT_GT(countColour(grabUntil([&](const QImage& image) { return countColour(image, kArrowMagenta) > 50; }), kArrowMagenta), 50);
  cue("State topic")->setValue("not a valid topic name!");
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "State").level == rviz::StatusProperty::Error; }));
  cue("Marching")->setValue(true);
  path_->subProp("Spacing mode")->setValue("Paper");
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Marching").present; }));
}

TEST_F(PathCuesTest, ThreeDStyleWithACueOnWarnsThatArrowsAreFlat)
{
  path_ = addPath("/test/plan", straightPath());
  ASSERT_NE(path_, nullptr);
  path_->subProp("Style")->setValue("3D");
  ASSERT_TRUE(waitFor([&] { return path_->spacedPath().has_destination; }));
  EXPECT_FALSE(statusOf(path_, "Style").text.contains("A cue is on")) << "no cue: 3D is drawn";
  cue("Horizon")->setValue(true);
  EXPECT_TRUE(waitFor([&] {
    return statusOf(path_, "Style").text.contains("A cue is on: arrows are drawn Flat (3D is not used with cues)");
  }));
  EXPECT_EQ(statusOf(path_, "Style").level, rviz::StatusProperty::Warn);
  cue("Horizon")->setValue(false);
  EXPECT_TRUE(waitFor([&] { return !statusOf(path_, "Style").text.contains("A cue is on"); })) << "no cue: no warning";
  cue("Marching")->setValue(true);
  EXPECT_TRUE(waitFor([&] { return statusOf(path_, "Style").text.contains("A cue is on"); }));
  path_->subProp("Style")->setValue("Flat");
  EXPECT_TRUE(waitFor([&] { return !statusOf(path_, "Style").present; })) << "Flat with a cue: no warning";
}
