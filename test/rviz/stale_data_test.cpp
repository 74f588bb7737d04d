// Stale data goes dark (issue 13): a ProjectedPath whose planner stopped publishing clears its
// arrows after "Path timeout"; a ProjectorCamera whose tf stopped blanks after "TF timeout"; and
// ProjectorCameraDisplay::health() reports what it does. Through the user's path: pluginlib class
// names, properties, topics, the output window's pixels as the X server has them.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <QScreen>
#include <QWindow>
#include <nav_msgs/Path.h>
#include <rviz/config.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>
#include <tf2_ros/transform_broadcaster.h>

#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "projector_test_fixture.h"

using namespace rviz_projector_test;
using rviz_projector::ProjectedPathDisplay;

namespace
{
const QRgb kDiscGreen = qRgb(0, 255, 0);
constexpr const char* kMovingFrame = "test_projector_moving_optical";

/// The demo path's poses, in map.
const std::vector<Vec2> kDemoPath{{0.5, 0.0}, {1.0, 0.02}, {1.5, 0.0}, {2.0, 0.0}};

nav_msgs::Path demoPathMessage()
{
  nav_msgs::Path path;
  path.header.frame_id = "map";
  for (const Vec2& p : kDemoPath)
  {
    geometry_msgs::PoseStamped pose;
    pose.header = path.header;
    pose.pose.position.x = p.x;
    pose.pose.position.y = p.y;
    pose.pose.orientation.w = 1;
    path.poses.push_back(pose);
  }
  return path;
}

bool allBlack(const QImage& image)
{
  return !image.isNull() && countColour(image, kBlack) == image.width() * image.height();
}

/// Seconds on the steady clock the test itself keeps (not the code under test's).
double steadyNow()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

class StaleDataTest : public ProjectorSceneTest
{
protected:
  /// The demo path: arrows and a destination disc in the lit area.
  ProjectedPathDisplay* demoPath()
  {
    return addPath("/test/plan", kDemoPath);
  }

  /// The projector's lens on the moving (broadcast, not static) frame.
  void useMovingFrame()
  {
    sensor_msgs::CameraInfo moving = info_;
    moving.header.frame_id = kMovingFrame;
    info_pub_.publish(moving);
  }

  /// The demo mount on the moving frame, stamped `age` seconds ago, moved by `dx` along x.
  void broadcast(double age, double dx = 0.0)
  {
    geometry_msgs::TransformStamped t =
        stampedTransform("map", kMovingFrame, kDemoMount.position.x + dx, kDemoMount.position.y,
                         kDemoMount.position.z, {kDemoMount.qx, kDemoMount.qy, kDemoMount.qz, kDemoMount.qw});
    t.header.stamp = ros::Time::now() - ros::Duration(age);
    tf_pub_.sendTransform(t);
  }

  Status transform() const { return statusOf(projector_, "Transform"); }

  tf2_ros::TransformBroadcaster tf_pub_;
};
}  // namespace

TEST_F(StaleDataTest, PathTimeoutClearsTheArrowsAndANewPathBringsThemBack)
{
  ProjectedPathDisplay* path = demoPath();
  ASSERT_NE(path, nullptr);
  EXPECT_EQ(path->subProp("Path timeout")->getValue().toDouble(), 0.0) << "default: never";
  ASSERT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100);

  // Timeout 1 s, then a new path: shown, and cleared about 1 s after it arrived.
  path->subProp("Path timeout")->setValue(1.0);
  const std::size_t builds = path->meshBuilds();
  const double published = steadyNow();
  path_pub_.publish(demoPathMessage());
  ASSERT_TRUE(waitFor([&] { return path->meshBuilds() > builds; })) << "the new path is drawn";
  ASSERT_TRUE(waitFor([&] { return path->spacedPath().arrows.empty(); }, 5.0)) << "cleared after the timeout";
  const double cleared_after = steadyNow() - published;
  EXPECT_GT(cleared_after, 0.9) << "not before the timeout";
  EXPECT_FALSE(path->spacedPath().has_destination);
  EXPECT_EQ(path->arrowTriangleCount(), 0u);
  EXPECT_EQ(path->circleTriangleCount(), 0u);
  const Status s = statusOf(path, "Path");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_NE(s.text.indexOf("No new path for"), -1) << s.text.toStdString();
  EXPECT_NE(s.text.indexOf("(Path timeout 1 s): arrows cleared"), -1) << s.text.toStdString();
  // The projector shows nothing of it: all black.
  const QImage dark = imagePart(grabWhen(allBlack));
  EXPECT_TRUE(allBlack(dark)) << countColour(dark, kArrowMagenta) << " magenta, " << countColour(dark, kDiscGreen)
                              << " green pixels left";

  // Raising the timeout does not bring the forgotten path back; a new path does (timeout 0: kept).
  path->subProp("Path timeout")->setValue(0.0);
  EXPECT_TRUE(path->spacedPath().arrows.empty());
  path_pub_.publish(demoPathMessage());
  ASSERT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); }));
  EXPECT_EQ(statusOf(path, "Path").level, rviz::StatusProperty::Ok) << statusOf(path, "Path").text.toStdString();
  EXPECT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100);
  // Timeout 0 never clears: still drawn well past the earlier 1 s.
  EXPECT_FALSE(waitFor([&] { return path->spacedPath().arrows.empty(); }, 2.0));
  EXPECT_GT(path->arrowTriangleCount(), 0u);
}

TEST_F(StaleDataTest, PathTimeoutLoweredLiveClearsAtOnce)
{
  ProjectedPathDisplay* path = demoPath();
  ASSERT_NE(path, nullptr);
  ASSERT_TRUE(waitFor([&] { return !path->spacedPath().arrows.empty(); }));
  ASSERT_FALSE(waitFor([&] { return path->spacedPath().arrows.empty(); }, 0.6)) << "default 0 keeps it";
  path->subProp("Path timeout")->setValue(0.5);  // the path is older than that already
  EXPECT_TRUE(path->spacedPath().arrows.empty()) << "cleared by the property change itself";
  path->subProp("Path timeout")->setValue(-3.0);
  EXPECT_EQ(path->subProp("Path timeout")->getValue().toDouble(), 0.0) << "negative: clamped to 0";
}

TEST_F(RvizTest, NegativeTimeoutsInAConfigAreClampedAndReported)
{
  const char* yaml = R"(
Displays:
  - Class: rviz_projector/ProjectedPath
    Name: Bad timeout
    Enabled: true
    Topic: /test/plan
    Path timeout: -3
  - Class: rviz_projector/ProjectorCamera
    Name: Bad tf timeout
    Enabled: false
    TF timeout: -1
)";
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readString(config, yaml);
  ASSERT_FALSE(reader.error()) << reader.errorMessage().toStdString();
  rviz_->manager()->load(config);
  rviz::DisplayGroup* root = rviz_->manager()->getRootDisplayGroup();
  ASSERT_EQ(root->numDisplays(), 2);
  rviz::Display* d = root->getDisplayAt(0);
  EXPECT_EQ(d->subProp("Path timeout")->getValue().toDouble(), 0.0);
  const Status s = statusOf(d, "Config");
  EXPECT_NE(s.text.indexOf("Path timeout: '-3'"), -1) << s.text.toStdString();
  rviz::Display* camera = root->getDisplayAt(1);
  EXPECT_EQ(camera->subProp("TF timeout")->getValue().toDouble(), 0.0);
  const Status c = statusOf(camera, "Config");
  EXPECT_NE(c.text.indexOf("TF timeout: '-1'"), -1) << c.text.toStdString();
}

TEST_F(StaleDataTest, StaleTfBlanksTheProjectorAndFreshTfBringsThePictureBack)
{
  EXPECT_NEAR(projector_->subProp("TF timeout")->getValue().toDouble(), 1.0, 1e-6) << "default 1 s";
  demoPath();
  // tf stamped 5 s ago from the start: the pose exists but is too old.
  useMovingFrame();
  ASSERT_TRUE(waitFor([&] {
    broadcast(5.0);
    return transform().level == rviz::StatusProperty::Error && transform().text.contains("s old");
  })) << transform().text.toStdString();
  const Status stale = transform();
  EXPECT_NE(stale.text.indexOf(QString("tf of '%1' in 'map' is ").arg(kMovingFrame)), -1)
      << stale.text.toStdString();
  EXPECT_NE(stale.text.indexOf("(TF timeout 1 s): projector blanked"), -1) << stale.text.toStdString();
  const QImage dark = imagePart(grabWhen(allBlack));
  EXPECT_TRUE(allBlack(dark)) << countColour(dark, kArrowMagenta) << " magenta pixels";
  rviz_projector::ProjectorCameraHealth h = projector_->health();
  EXPECT_TRUE(h.blanked);
  EXPECT_FALSE(h.pose_ok);
  EXPECT_NE(h.blank_reason.find("projector blanked"), std::string::npos) << h.blank_reason;
  EXPECT_NEAR(h.tf_age_s, 5.0, 0.5) << "the stamp published was 5 s old";

  // TF timeout 0: never stale, the old pose is used.
  projector_->subProp("TF timeout")->setValue(0.0);
  EXPECT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100);
  EXPECT_EQ(transform().level, rviz::StatusProperty::Ok);
  projector_->subProp("TF timeout")->setValue(1.0);
  EXPECT_TRUE(allBlack(imagePart(grabWhen(allBlack))));

  // Fresh tf: the picture comes back.
  const QImage back = imagePart(grabWhen([&](const QImage& image) {
    broadcast(0.0);
    return countColour(image, kArrowMagenta) > 100;
  }));
  EXPECT_GT(countColour(back, kArrowMagenta), 100);
  EXPECT_EQ(transform().level, rviz::StatusProperty::Ok) << transform().text.toStdString();
  h = projector_->health();
  EXPECT_FALSE(h.blanked) << h.blank_reason;
  EXPECT_TRUE(h.pose_ok);
  EXPECT_GE(h.tf_age_s, 0.0);
  EXPECT_LT(h.tf_age_s, 1.0);

  // tf stops: dark again after about the timeout.
  const double last_sent = steadyNow();
  broadcast(0.0);
  ASSERT_TRUE(waitFor([&] { return transform().level == rviz::StatusProperty::Error; }, 5.0));
  EXPECT_GT(steadyNow() - last_sent, 0.9) << "not before the timeout";
  EXPECT_TRUE(allBlack(imagePart(grabWhen(allBlack))));
}

TEST_F(StaleDataTest, StaticOnlyChainNeverBlanks)
{
  // The fixture's mount is a static transform (stamp 0 in tf): never stale, however short the timeout.
  demoPath();
  projector_->subProp("TF timeout")->setValue(0.05);
  EXPECT_FALSE(waitFor([&] { return transform().level != rviz::StatusProperty::Ok || projector_->health().blanked; },
                       1.0))
      << transform().text.toStdString();
  EXPECT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100);
  const rviz_projector::ProjectorCameraHealth h = projector_->health();
  EXPECT_EQ(h.tf_age_s, 0.0) << "a static chain";
  EXPECT_TRUE(h.pose_ok);
  EXPECT_FALSE(h.blanked);
}

TEST_F(StaleDataTest, HealthMatchesWhatTheTestSees)
{
  demoPath();
  grabWithArrows();
  // The window, as Qt has it.
  rviz_projector::ProjectorCameraHealth h = projector_->health();
  ASSERT_NE(projector_->outputWindow(), nullptr);
  QWindow* window = projector_->outputWindow()->windowHandle();
  ASSERT_NE(window, nullptr);
  EXPECT_TRUE(h.window_shown);
  EXPECT_EQ(h.full_screen, bool(window->windowStates() & Qt::WindowFullScreen));
  ASSERT_NE(window->screen(), nullptr);
  EXPECT_EQ(h.screen_name, window->screen()->name().toStdString());
  EXPECT_TRUE(h.screen_connected);
  EXPECT_TRUE(h.has_lens);

  // The CameraInfo came once (latched): its age grows between two reads.
  const double info_age = h.camera_info_age_s;
  ASSERT_TRUE(std::isfinite(info_age));
  EXPECT_GE(info_age, 0.0);
  ASSERT_TRUE(waitFor([&] { return projector_->health().camera_info_age_s > info_age + 0.3; }));
  info_pub_.publish(info_);
  ASSERT_TRUE(waitFor([&] { return projector_->health().camera_info_age_s < 0.3; })) << "a new one resets it";

  // Frames: the counters are the display's; the rate is judged against frames the test counts
  // while it keeps the scene changing (the projector moving a little at each step).
  useMovingFrame();
  int step = 0;
  ASSERT_TRUE(waitFor([&] {
    broadcast(0.0, 0.001 * (++step % 2));
    return transform().level == rviz::StatusProperty::Ok && projector_->hasLens();
  }));
  const std::uint64_t frames0 = projector_->framesRendered();
  const double t0 = steadyNow();
  waitFor([&] {
    broadcast(0.0, 0.001 * (++step % 2));
    return steadyNow() - t0 > 2.5;
  }, 5.0);
  h = projector_->health();
  const double measured = double(projector_->framesRendered() - frames0) / (steadyNow() - t0);
  std::printf("  frame rate: health %.1f/s, counted %.1f/s\n", h.frame_rate_hz, measured);
  EXPECT_GT(measured, 1.0) << "moving tf renders frames";
  EXPECT_NEAR(h.frame_rate_hz, measured, 0.35 * measured + 1.0);
  EXPECT_EQ(h.frames_rendered, projector_->framesRendered());
  EXPECT_EQ(h.frames_skipped, projector_->framesSkipped());
  EXPECT_GE(h.seconds_since_last_frame, 0.0);
  EXPECT_LT(h.seconds_since_last_frame, 0.5);

  // Back on the static mount, nothing changes: no frames, the rate falls.
  info_pub_.publish(info_);
  ASSERT_TRUE(waitFor([&] { return transform().level == rviz::StatusProperty::Ok && projector_->health().tf_age_s == 0.0; }));
  ASSERT_TRUE(waitFor([&] { return projector_->health().seconds_since_last_frame > 1.0; }, 5.0))
      << "no frames while nothing changes";
  EXPECT_LT(projector_->health().frame_rate_hz, 0.6 * measured);
}

TEST_F(ProjectorCameraTest, HealthWithoutCameraInfo)
{
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "CameraInfo").present; }));
  const rviz_projector::ProjectorCameraHealth h = projector_->health();
  EXPECT_FALSE(h.has_lens);
  EXPECT_TRUE(std::isnan(h.camera_info_age_s));
  EXPECT_TRUE(std::isnan(h.tf_age_s));
  EXPECT_FALSE(h.pose_ok);
  EXPECT_TRUE(h.blanked);
  EXPECT_NE(h.blank_reason.find("No CameraInfo received"), std::string::npos) << h.blank_reason;
}
