// ProjectorCamera in a real rviz: created through pluginlib, fed CameraInfo and tf, checked by the
// pixels of its output window against the independent oracle of projector_test_fixture.h
// (image_geometry on the raw CameraInfo, the letterbox by hand), and by its statuses. The pixel
// accuracy of lenses, Tx/Ty, binning, ROI and letterbox sizes: projector_pixels_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <OgreRenderSystem.h>
#include <OgreRenderSystemCapabilities.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <QApplication>
#include <QGuiApplication>
#include <QImage>
#include <QKeyEvent>
#include <QScreen>
#include <QThread>
#include <QWindow>
#include <nav_msgs/Path.h>
#include <ros/callback_queue.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/render_panel.h>
#include <rviz/visualization_manager.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Empty.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>

#include "rviz_projector/displays/main_view_cost.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "projector_test_fixture.h"
#include "robustness_helpers.h"

using rviz_projector::ProjectorCameraDisplay;
using rviz_projector::Vec2;
using rviz_projector::Vec3;
using rviz_projector_test::bodyMount;
using rviz_projector_test::countColour;
using rviz_projector_test::greenCentroid;
using rviz_projector_test::kArrowMagenta;
using rviz_projector_test::kBlack;
using rviz_projector_test::kDemoMount;
using rviz_projector_test::kInfoTopic;
using rviz_projector_test::kOpticalFrame;
using rviz_projector_test::Letterbox;
using rviz_projector_test::Mount;
using rviz_projector_test::PixelOracle;
using rviz_projector_test::ProjectorCameraTest;
using rviz_projector_test::ProjectorSceneTest;
using rviz_projector_test::Status;

namespace
{

sensor_msgs::CameraInfo cameraInfo(unsigned w, unsigned h, double f, double cx, double cy)
{
  return rviz_projector_test::projectorInfo(w, h, f, cx, cy);
}

int visibleProjectorWindows()
{
  int n = 0;
  for (QWidget* w : QApplication::topLevelWidgets())
  {
    if (qobject_cast<rviz_projector::ProjectorOutputWindow*>(w) && w->isVisible())
    {
      ++n;
    }
  }
  return n;
}

QScreen* screenNamed(const QString& name)
{
  for (QScreen* s : QGuiApplication::screens())
  {
    if (s->name() == name)
    {
      return s;
    }
  }
  return nullptr;
}
}  // namespace

TEST_F(ProjectorSceneTest, ArrowsReachTheProjectorAndVisibilityHidesThem)
{
  std::vector<Vec2> points;
  for (double x = 0.5; x <= 2.3; x += 0.037)
  {
    points.push_back({x, 0.05 * std::sin(2 * x)});
  }
  auto* path = addPath("/test/plan", points);
  ASSERT_NE(path, nullptr);
  const QImage frame = imagePart(grabWithArrows(500));
  ASSERT_FALSE(frame.isNull());
  int checked = 0;
  const auto& arrows = path->spacedPath().arrows;
  for (std::size_t k = 0; k < arrows.size(); ++k)
  {
    // Middle of the shaft: 30% of the way from tail to tip, on the arrow's axis.
    const Vec2 shaft = arrows[k].tail + (arrows[k].tip - arrows[k].tail) * 0.3;
    const Vec2 px = windowPixel(shaft);
    if (px.x < 2 || px.y < 2 || px.x > frame.width() - 3 || px.y > frame.height() - 3)
    {
      continue;  // outside the lit area
    }
    EXPECT_TRUE(rviz_projector_test::sameColour(frame.pixel(int(std::lround(px.x)), int(std::lround(px.y))),
                                                kArrowMagenta, 30))
        << "arrow " << k << " at pixel " << px.x << "," << px.y;
    // Halfway between this arrow's tail and the next arrow's tip: floor, i.e. black.
    if (k + 1 < arrows.size())
    {
      const Vec2 gap = windowPixel(arrows[k].tail + (arrows[k + 1].tip - arrows[k].tail) * 0.5);
      EXPECT_TRUE(rviz_projector_test::sameColour(frame.pixel(int(std::lround(gap.x)), int(std::lround(gap.y))),
                                                  kBlack, 30))
          << "gap after arrow " << k;
    }
    // Well beside the path: black.
    const Vec2 beside = windowPixel(shaft + Vec2{0.0, 0.25});
    if (beside.x > 0 && beside.y > 0 && beside.x < frame.width() && beside.y < frame.height())
    {
      EXPECT_EQ(frame.pixel(int(beside.x), int(beside.y)), kBlack);
    }
    ++checked;
  }
  EXPECT_GE(checked, 3) << "the demo set-up should show several arrows";
  EXPECT_GT(countColour(frame, kArrowMagenta), 500);

  // Untick the path in the projector's Visibility: the projection goes all black.
  rviz::Property* visibility = projector_->subProp("Visibility");
  rviz::Property* entry = visibility->subProp("Projected path");
  ASSERT_NE(entry->getName(), QString()) << "Visibility lists the path display";
  entry->setValue(false);
  const QImage hidden = imagePart(grabWhen([&](const QImage& image) { return countColour(image, kArrowMagenta) == 0; }));
  EXPECT_EQ(countColour(hidden, kArrowMagenta), 0);
  EXPECT_EQ(countColour(hidden, kBlack), hidden.width() * hidden.height());
}

TEST_F(ProjectorSceneTest, OnlyThisPackagesPathDisplaysAreVisibleByDefault)
{
  // A grid on the floor in the projector's view, opaque, bright and thick: were it projected, its
  // lines x = 1 m and x = 2 m would cross the lit area as wide yellow bands.
  rviz::Display* grid = rviz_->addDisplay("rviz/Grid", "Grid");
  ASSERT_NE(grid, nullptr);
  const QRgb yellow = qRgb(255, 255, 0);
  grid->subProp("Color")->setValue(QColor(255, 255, 0));
  grid->subProp("Alpha")->setValue(1.0);
  grid->subProp("Line Style")->setValue("Billboards");
  grid->subProp("Line Style")->subProp("Line Width")->setValue(0.05);
  // Our path comes after the grid is yellow, so the frame that shows the path shows the grid as
  // it is now, if at all.
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  rviz::Property* visibility = projector_->subProp("Visibility");
  EXPECT_EQ(visibility->subProp("Grid")->getValue().toBool(), false);
  EXPECT_EQ(visibility->subProp("Projected path")->getValue().toBool(), true);
  const QImage frame = imagePart(grabWithArrows());
  EXPECT_GT(countColour(frame, kArrowMagenta), 100) << "the path is projected";
  EXPECT_EQ(countColour(frame, yellow), 0) << "the grid is not";
  // The check can see the grid: ticked in Visibility, it is projected.
  visibility->subProp("Grid")->setValue(true);
  const QImage ticked = imagePart(grabWhen([&](const QImage& image) { return countColour(image, yellow) > 1000; }));
  EXPECT_GT(countColour(ticked, yellow), 1000) << "a ticked grid is projected";
}

TEST_F(ProjectorSceneTest, BadCameraInfoIsReportedAndShowsBackgroundOnly)
{
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case
  {
    const char* what;
    std::function<void(sensor_msgs::CameraInfo&)> spoil;
    const char* status;
  };
  const Case cases[] = {
      {"zero width", [](sensor_msgs::CameraInfo& i) { i.width = 0; }, "image size is 0x800"},
      {"zero height", [](sensor_msgs::CameraInfo& i) { i.height = 0; }, "image size is 1280x0"},
      {"NaN focal length", [nan](sensor_msgs::CameraInfo& i) { i.P[0] = nan; }, "P[0] is not finite"},
      {"zero focal length", [](sensor_msgs::CameraInfo& i) { i.P[0] = 0; }, "focal length in P is not positive"},
      {"negative focal length", [](sensor_msgs::CameraInfo& i) { i.P[5] = -1300; }, "focal length in P is not positive"},
      {"K and P zero", [](sensor_msgs::CameraInfo& i) { i.K.fill(0); i.P.fill(0); }, "P and K are all zero"},
      {"giant image", [](sensor_msgs::CameraInfo& i) { i.width = 20000; i.height = 20000; }, "exceeds the 16384x16384"},
      {"NaN in K with zero P", [nan](sensor_msgs::CameraInfo& i) { i.P.fill(0); i.K[2] = nan; }, "K[2] is not finite"},
  };
  for (const Case& c : cases)
  {
    sensor_msgs::CameraInfo bad = info_;
    c.spoil(bad);
    info_pub_.publish(bad);
    ASSERT_TRUE(waitFor([&] { return !projector_->hasLens(); })) << c.what;
    const Status s = statusOf(projector_, "CameraInfo");
    EXPECT_EQ(s.level, rviz::StatusProperty::Error) << c.what;
    EXPECT_NE(s.text.indexOf(c.status), -1) << c.what << ": " << s.text.toStdString();
    auto allBlack = [&](const QImage& image) { return countColour(image, kBlack) == image.width() * image.height(); };
    const QImage frame = imagePart(grabWhen(allBlack));
    EXPECT_TRUE(allBlack(frame)) << c.what << ": background only";
    EXPECT_FALSE(rviz_->renderMainView().isNull()) << "rviz keeps rendering";
    info_pub_.publish(info_);  // good again
    ASSERT_TRUE(waitFor([&] { return projector_->hasLens(); })) << c.what;
  }
  // A plumb_bob D is drawn through the warp (issue 24; its pixels: projector_pixels_test.cpp) and
  // says so; the same D under a model that cannot be drawn is a warning.
  sensor_msgs::CameraInfo distorted = info_;
  distorted.distortion_model = "plumb_bob";
  distorted.D = {0.1, -0.05, 0, 0, 0};
  info_pub_.publish(distorted);
  ASSERT_TRUE(waitFor([&] {
    const Status s = statusOf(projector_, "Distortion");
    return s.present && s.level == rviz::StatusProperty::Ok;
  })) << statusOf(projector_, "Distortion").text.toStdString();
  const std::string drawn = statusOf(projector_, "Distortion").text.toStdString();
  EXPECT_EQ(drawn.rfind("plumb_bob, D = 0.1 -0.05 0 0 0: drawn through a 32x20 warp", 0), 0u) << drawn;
  distorted.distortion_model = "equidistant";
  info_pub_.publish(distorted);
  ASSERT_TRUE(waitFor([&] {
    const Status s = statusOf(projector_, "Distortion");
    return s.present && s.level == rviz::StatusProperty::Warn;
  }));
  EXPECT_TRUE(statusOf(projector_, "Distortion").text.startsWith("distortion D is not applied"))
      << statusOf(projector_, "Distortion").text.toStdString();
  info_pub_.publish(info_);
  ASSERT_TRUE(waitFor([&] { return !statusOf(projector_, "Distortion").present; })) << "D zero: no status";
}

TEST_F(ProjectorSceneTest, UnknownFrameIsAnErrorAndBlanksTheView)
{
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  sensor_msgs::CameraInfo lost = info_;
  lost.header.frame_id = "nowhere_optical";
  info_pub_.publish(lost);
  ASSERT_TRUE(waitFor([&] {
    const Status s = statusOf(projector_, "Transform");
    return s.present && s.level == rviz::StatusProperty::Error;
  }, 5.0)) << statusOf(projector_, "Transform").text.toStdString();
  projector_->renderNow();
  const Status s = statusOf(projector_, "Transform");
  EXPECT_NE(s.text.indexOf("nowhere_optical"), -1) << s.text.toStdString();
  auto allBlack = [&](const QImage& image) { return countColour(image, kBlack) == image.width() * image.height(); };
  const QImage frame = imagePart(grabWhen(allBlack));
  EXPECT_TRUE(allBlack(frame));
  // The Frame property overrides the header's frame.
  projector_->subProp("Frame")->setValue(kOpticalFrame);
  const QImage fixed = imagePart(grabWithArrows());
  EXPECT_GT(countColour(fixed, kArrowMagenta), 100);
  EXPECT_EQ(statusOf(projector_, "Transform").level, rviz::StatusProperty::Ok);
}

TEST_F(ProjectorSceneTest, StaleCameraInfoStampStillRenders)
{
  // The projector's frame exists in tf only from now on: broadcast (not static, which would hold
  // at every time), and moved from the demo mount. A CameraInfo stamped long ago (as a latched
  // one often is) must still project with the latest pose; a display that looked the pose up at
  // the CameraInfo's stamp would find none and show nothing.
  constexpr const char* kMovingFrame = "test_projector_moving_optical";
  Mount moved = kDemoMount;
  moved.position.y += 0.1;
  tf2_ros::TransformBroadcaster tf_pub;
  auto broadcast = [&] {
    tf_pub.sendTransform(rviz_projector_test::stampedTransform(
        "map", kMovingFrame, moved.position.x, moved.position.y, moved.position.z, {moved.qx, moved.qy, moved.qz, moved.qw}));
  };
  const Vec2 target{1.2, 0.0};
  addTarget(target, 0.04);
  ASSERT_TRUE(waitFor([&] { return targetsReady(); }));
  const ros::Time long_ago(1.0);
  auto& tf = *rviz_->manager()->getTF2BufferPtr();
  ASSERT_TRUE(waitFor([&] {
    broadcast();
    return tf.canTransform("map", kMovingFrame, ros::Time(0));
  })) << "the broadcast transform arrives";
  ASSERT_FALSE(tf.canTransform("map", kMovingFrame, long_ago)) << "no pose at the CameraInfo's stamp";

  sensor_msgs::CameraInfo old = info_;
  old.header.frame_id = kMovingFrame;
  old.header.stamp = long_ago;
  info_pub_.publish(old);
  const PixelOracle oracle(old, moved);
  Vec2 centroid, expected;
  int count = 0;
  grabWhen([&](const QImage& window) {
    broadcast();
    expected = oracle.toWindow(oracle.box(window.width(), window.height()), oracle.imagePixel(target));
    return greenCentroid(window, expected, 60, centroid, count) && rviz_projector::distance(centroid, expected) < 1.0;
  });
  EXPECT_GT(count, 50) << "the target is projected";
  EXPECT_LT(rviz_projector::distance(centroid, expected), 1.0)
      << "target at " << centroid.x << "," << centroid.y << ", expected " << expected.x << "," << expected.y;
  EXPECT_EQ(statusOf(projector_, "Transform").level, rviz::StatusProperty::Ok);
}

TEST_F(ProjectorSceneTest, FootprintStatusGivesTheLitArea)
{
  projector_->renderNow();
  const Status s = statusOf(projector_, "Footprint");
  ASSERT_TRUE(s.present);
  EXPECT_EQ(s.level, rviz::StatusProperty::Ok);
  EXPECT_TRUE(s.text.startsWith("Lit floor area")) << s.text.toStdString();
  // Aim above the horizon: part of the image misses the floor.
  mount(bodyMount({0.0, 0.0, 1.2}, 0.0, 0.1, 0.0));
  EXPECT_TRUE(waitFor([&] {
    projector_->renderNow();
    return statusOf(projector_, "Footprint").level == rviz::StatusProperty::Warn;
  })) << statusOf(projector_, "Footprint").text.toStdString();
}

TEST_F(ProjectorSceneTest, TestPatternDrawsAMetricGrid)
{
  projector_->subProp("Test pattern")->setValue("Metric grid");
  const QImage frame =
      imagePart(grabWhen([&](const QImage& image) { return countColour(image, qRgb(255, 255, 255)) > 2000; }));
  // Bold metre line x = 1 m across the floor: white at its projection.
  const Vec2 on_line = windowPixel({1.0, 0.0});
  Vec2 off_line = windowPixel({1.05, 0.03});
  EXPECT_TRUE(rviz_projector_test::sameColour(frame.pixel(int(std::lround(on_line.x)), int(std::lround(on_line.y))),
                                              qRgb(255, 255, 255), 30));
  EXPECT_EQ(frame.pixel(int(std::lround(off_line.x)), int(std::lround(off_line.y))), kBlack);
  EXPECT_GT(countColour(frame, qRgb(255, 255, 255)), 2000);
  projector_->subProp("Test pattern")->setValue("Off");
  EXPECT_EQ(countColour(imagePart(grabWhen([&](const QImage& image) {
                          return countColour(image, qRgb(255, 255, 255)) == 0;
                        })),
                        qRgb(255, 255, 255)),
            0);
}

TEST_F(ProjectorCameraTest, MultisampledMainViewOnASoftwareRendererIsReported)
{
  // The test X server has no GPU: rviz renders with Mesa llvmpipe and, as installed, with 4x
  // anti-aliasing in its main view, the set-up that holds the projector window back.
  const unsigned int fsaa = rviz_->panel()->getRenderWindow()->getFSAA();
  const std::string renderer = Ogre::Root::getSingleton().getRenderSystem()->getCapabilities()->getDeviceName();
  if (fsaa <= 1 || !rviz_projector::isSoftwareRenderer(renderer))
  {
    GTEST_SKIP() << "main view " << fsaa << "x anti-aliasing on '" << renderer << "': nothing to report";
  }
  Status s = statusOf(projector_, "Main view");
  ASSERT_TRUE(s.present);
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_NE(s.text.indexOf("--disable-anti-aliasing"), -1) << s.text.toStdString();
  EXPECT_NE(s.text.indexOf(QString::number(fsaa) + "x"), -1) << s.text.toStdString();
  // Reset clears statuses; this one still holds.
  projector_->reset();
  EXPECT_TRUE(statusOf(projector_, "Main view").present);
}

TEST_F(ProjectorCameraTest, LifecycleLeavesNoStrayWindowsAndNoVisibilityBitLeak)
{
  info_pub_.publish(cameraInfo(640, 400, 600, 319.5, 199.5));
  ASSERT_TRUE(waitFor([&] { return visibleProjectorWindows() == 1; }));
  projector_->setEnabled(false);
  ASSERT_TRUE(waitFor([&] { return visibleProjectorWindows() == 0; }));
  projector_->setEnabled(true);
  ASSERT_TRUE(waitFor([&] { return visibleProjectorWindows() == 1; }));

  // Two projectors: two windows, two visibility bits.
  auto* second = dynamic_cast<ProjectorCameraDisplay*>(rviz_->addDisplay("rviz_projector/ProjectorCamera", "P2"));
  ASSERT_NE(second, nullptr);
  second->subProp("Topic")->setValue(kInfoTopic);
  ASSERT_TRUE(waitFor([&] { return visibleProjectorWindows() == 2; }));
  EXPECT_NE(second->visibilityBit(), 0u);
  EXPECT_NE(second->visibilityBit(), projector_->visibilityBit());
  delete second;
  ASSERT_TRUE(waitFor([&] { return visibleProjectorWindows() == 1; }));

  // Many add/remove cycles: visibility bits are freed (there are only 32).
  for (int i = 0; i < 40; ++i)
  {
    rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectorCamera", "cycle");
    auto* p = dynamic_cast<ProjectorCameraDisplay*>(d);
    ASSERT_NE(p, nullptr);
    ASSERT_NE(p->visibilityBit(), 0u) << "cycle " << i;
    d->setEnabled(false);
    d->setEnabled(true);
    QApplication::processEvents();
    delete d;
  }
  EXPECT_TRUE(waitFor([&] { return visibleProjectorWindows() == 1; })) << visibleProjectorWindows() << " windows";
  delete projector_;
  projector_ = nullptr;
  EXPECT_TRUE(waitFor([&] { return visibleProjectorWindows() == 0; })) << visibleProjectorWindows() << " windows";
}

TEST_F(ProjectorCameraTest, FullScreenOnTheProjectorScreenFollowsUnplugAndReplug)
{
  if (QGuiApplication::screens().size() < 2 || !screenNamed("DUMMY1"))
  {
    GTEST_SKIP() << "needs the two-screen dummy X server (scripts/test starts one)";
  }
  info_pub_.publish(cameraInfo(1280, 800, 1300, 639.5, 399.5));
  ASSERT_TRUE(waitFor([&] { return projector_->hasLens() && visibleProjectorWindows() == 1; }));
  rviz_projector::ProjectorOutputWindow* window = projector_->outputWindow();
  // Automatic: the screen rviz is not on (rviz is on the primary, DUMMY0).
  ASSERT_TRUE(waitFor([&] { return window->geometry() == screenNamed("DUMMY1")->geometry(); }))
      << "window at " << window->geometry().x() << "," << window->geometry().y();
  EXPECT_TRUE(window->isFullScreenOn());
  EXPECT_EQ(statusOf(projector_, "Output").level, rviz::StatusProperty::Ok);
  EXPECT_EQ(window->size(), QSize(1280, 800));  // the 1280x800 image 1:1 on the 1280x800 screen

  // Unplug the projector: the window goes to the remaining screen, windowed, with a warning.
  ASSERT_EQ(std::system("xrandr --output DUMMY1 --off"), 0);
  ASSERT_TRUE(waitFor([&] { return QGuiApplication::screens().size() == 1; }, 5.0));
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Output").level == rviz::StatusProperty::Warn; }));
  window = projector_->outputWindow();
  ASSERT_NE(window, nullptr);
  EXPECT_FALSE(window->isFullScreenOn()) << "never cover rviz on the only screen";
  EXPECT_TRUE(QGuiApplication::primaryScreen()->geometry().contains(window->geometry()));
  EXPECT_FALSE(rviz_->renderMainView().isNull()) << "rviz keeps running";

  // Plug it back in: full screen on it again.
  ASSERT_EQ(std::system("xrandr --output DUMMY1 --mode 1280x800_60 --right-of DUMMY0"), 0);
  ASSERT_TRUE(waitFor([&] { return screenNamed("DUMMY1") != nullptr; }, 5.0));
  ASSERT_TRUE(waitFor([&] {
    return projector_->outputWindow()->isFullScreenOn() &&
           projector_->outputWindow()->geometry() == screenNamed("DUMMY1")->geometry();
  }));
  EXPECT_EQ(statusOf(projector_, "Output").level, rviz::StatusProperty::Ok);

  // An explicit choice of a screen that does not exist: warning, falls back to automatic.
  projector_->subProp("Output screen")->setValue("HDMI-9");
  const Status s = statusOf(projector_, "Output");
  EXPECT_EQ(s.level, rviz::StatusProperty::Warn);
  EXPECT_NE(s.text.indexOf("Screen 'HDMI-9' is not connected"), -1) << s.text.toStdString();
  // Explicitly the primary screen: full screen there.
  projector_->subProp("Output screen")->setValue("DUMMY0");
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow()->geometry() == screenNamed("DUMMY0")->geometry(); }));
  // Full screen off: a normal window.
  projector_->subProp("Full screen")->setValue(false);
  ASSERT_TRUE(waitFor([&] { return !projector_->outputWindow()->isFullScreenOn(); }));
  EXPECT_EQ(visibleProjectorWindows(), 1);
}

namespace
{
/// Runs only Qt's event loop (timers, queued calls), no ros::spinOnce() from the test: whatever
/// reaches the projector then got there through the display's own timer.
void pumpQt(double seconds)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(seconds);
  while (ros::WallTime::now() < end)
  {
    QApplication::processEvents(QEventLoop::AllEvents, 5);
    QThread::msleep(2);
  }
}

/// pumpQt until `done` holds or `timeout` seconds pass; returns done().
bool pumpQtUntil(const std::function<bool()>& done, double timeout = 5.0)
{
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(timeout);
  while (!done() && ros::WallTime::now() < end)
  {
    pumpQt(0.01);
  }
  return done();
}

/// A two-pose path in map from x = 0.5 to x = 2.0 m at `y`.
nav_msgs::Path pathAlongX(double y)
{
  return rviz_projector_test::makePath("map", {Vec3{0.5, y, 0.0}, Vec3{2.0, y, 0.0}});
}

/// The output window's pixels as the X server has them, without rendering.
QImage peek(rviz_projector::ProjectorOutputWindow* window)
{
  QScreen* screen = window->windowHandle() ? window->windowHandle()->screen() : QGuiApplication::primaryScreen();
  return screen->grabWindow(window->winId()).toImage().convertToFormat(QImage::Format_RGB888);
}
}  // namespace

TEST_F(ProjectorSceneTest, RendersOnChangeWithoutRvizUpdatesAndNotOtherwise)
{
  auto* path = addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  ASSERT_NE(path, nullptr);
  // rviz's main view stops updating (as if minimised, or its frame rate were tiny); the main
  // window is hidden. The projector keeps its own timer.
  rviz_->manager()->stopUpdate();
  rviz_->panel()->hide();
  rviz_projector::ProjectorOutputWindow* window = projector_->outputWindow();
  ASSERT_TRUE(pumpQtUntil([&] { return countColour(peek(window), kArrowMagenta) > 100; }));
  ASSERT_TRUE(pumpQtUntil([&] {
    const std::uint64_t before = projector_->framesRendered();
    pumpQt(0.2);
    return projector_->framesRendered() == before;
  })) << "the projector never settled";

  // Nothing changes: no new frames.
  const std::uint64_t rendered = projector_->framesRendered();
  const std::uint64_t skipped = projector_->framesSkipped();
  pumpQt(0.5);
  EXPECT_EQ(projector_->framesRendered(), rendered) << "re-rendered an unchanged view";
  EXPECT_GT(projector_->framesSkipped(), skipped);

  // A new path (arrows elsewhere) reaches the window through the projector's own timer.
  path_pub_.publish(pathAlongX(0.15));
  // The old path's arrow nearest the middle of the lit area, moved sideways by 0.15 m.
  Vec2 old_mid{0.0, 0.0};
  for (const auto& a : path->spacedPath().arrows)
  {
    const Vec2 mid = a.tail * 0.5 + a.tip * 0.5;
    if (std::abs(mid.x - 1.1) < std::abs(old_mid.x - 1.1))
    {
      old_mid = mid;
    }
  }
  const Vec2 new_arrow = windowPixel(old_mid + Vec2{0.0, 0.15});
  bool arrived = false;
  const ros::WallTime end = ros::WallTime::now() + ros::WallDuration(5.0);
  while (!arrived && ros::WallTime::now() < end)
  {
    pumpQt(0.05);
    const QImage frame = peek(window);
    const Letterbox box = PixelOracle(info_, kDemoMount).box(frame.width(), frame.height());
    arrived = rviz_projector_test::sameColour(
        frame.pixel(box.left + int(std::lround(new_arrow.x)), box.top + int(std::lround(new_arrow.y))), kArrowMagenta,
        30);
  }
  EXPECT_TRUE(arrived) << "the new path never reached the projector window";
  EXPECT_GT(projector_->framesRendered(), rendered);
  rviz_->manager()->startUpdate();
}

TEST_F(ProjectorSceneTest, RepeatedUnchangedCameraInfoRendersNothing)
{
  // Issue 23, defect 1: camera drivers and `rostopic pub -r 30` publish the same CameraInfo with
  // every frame, each with a new stamp. Such a message is no event: no frame is rendered for it.
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  rviz_->manager()->stopUpdate();  // only the projector's own timer renders
  rviz_projector::ProjectorOutputWindow* window = projector_->outputWindow();
  ASSERT_TRUE(pumpQtUntil([&] { return countColour(peek(window), kArrowMagenta) > 100; }));
  ASSERT_TRUE(pumpQtUntil([&] {
    const std::uint64_t before = projector_->framesRendered();
    pumpQt(0.2);
    return projector_->framesRendered() == before;
  })) << "the projector never settled";

  const std::uint64_t rendered = projector_->framesRendered();
  const std::uint64_t handled = projector_->cameraInfoMessages();
  sensor_msgs::CameraInfo repeat = info_;
  for (int i = 1; i <= 10; ++i)
  {
    repeat.header.stamp = ros::Time::now();
    info_pub_.publish(repeat);
    // The display handles a message in its frame timer, right before it decides to render.
    ASSERT_TRUE(pumpQtUntil([&] { return projector_->cameraInfoMessages() >= handled + i; }))
        << "CameraInfo " << i << " never reached the display";
  }
  EXPECT_EQ(projector_->framesRendered(), rendered) << "an unchanged CameraInfo rendered a frame";
  EXPECT_EQ(projector_->health().camera_info_messages, handled + 10);

  // Positive control: a changed lens renders.
  repeat.K[0] = repeat.P[0] = info_.K[0] * 1.1;
  info_pub_.publish(repeat);
  EXPECT_TRUE(pumpQtUntil([&] {
    return std::abs(projector_->lens().fx() - info_.K[0] * 1.1) < 1e-9 && projector_->framesRendered() > rendered;
  })) << "a changed lens was not rendered (fx " << projector_->lens().fx() << ")";
  rviz_->manager()->startUpdate();
}

TEST_F(ProjectorSceneTest, RenderingNeverRunsCallbacksOfRvizsGlobalQueue)
{
  // Issue 11, defect 2: the display never spins ROS's global callback queue. rviz owns it, and one
  // of its callbacks (~load_config) deletes every display, this one included. A message waits in
  // the global queue while only Qt's event loop runs (rviz's update stopped) and the projector
  // renders frame after frame: its callback must not run until the test itself spins.
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  rviz_->manager()->stopUpdate();
  int calls = 0;
  ros::Subscriber probe = nh_.subscribe<std_msgs::Empty>("/test/global_queue_probe", 1,
                                                         [&calls](const std_msgs::Empty::ConstPtr&) { ++calls; });
  ros::Publisher probe_pub = nh_.advertise<std_msgs::Empty>("/test/global_queue_probe", 1);
  ASSERT_TRUE(pumpQtUntil([&] { return probe_pub.getNumSubscribers() > 0; }));
  probe_pub.publish(std_msgs::Empty());
  ASSERT_TRUE(pumpQtUntil([] { return !ros::getGlobalCallbackQueue()->isEmpty(); }))
      << "the probe message never reached the global queue";
  // New paths through the path display's own queue keep the projector rendering.
  const std::uint64_t rendered = projector_->framesRendered();
  for (int i = 1; i <= 10; ++i)
  {
    path_pub_.publish(pathAlongX(0.02 * i));
    const std::uint64_t before = projector_->framesRendered();
    pumpQtUntil([&] { return projector_->framesRendered() > before; }, 2.0);
  }
  EXPECT_GE(projector_->framesRendered(), rendered + 5) << "the projector did not render while the probe waited";
  EXPECT_EQ(calls, 0) << "a callback of the global queue ran inside the display";
  // Positive control: the message is there, and the test's own spin delivers it.
  ros::spinOnce();
  EXPECT_EQ(calls, 1);
  rviz_->manager()->startUpdate();
}

TEST_F(ProjectorSceneTest, ImageOutputPublishesTheRenderedView)
{
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  sensor_msgs::Image::ConstPtr image;
  sensor_msgs::CameraInfo::ConstPtr info;
  ros::Subscriber image_sub = nh_.subscribe<sensor_msgs::Image>(
      "/test/rendered/image", 1, [&](const sensor_msgs::Image::ConstPtr& m) { image = m; });
  ros::Subscriber info_sub = nh_.subscribe<sensor_msgs::CameraInfo>(
      "/test/rendered/camera_info", 1, [&](const sensor_msgs::CameraInfo::ConstPtr& m) { info = m; });
  projector_->subProp("Image output")->subProp("Image topic")->setValue("/test/rendered/image");
  projector_->subProp("Image output")->subProp("Image rate")->setValue(20.0);
  projector_->subProp("Image output")->setValue(true);
  ASSERT_TRUE(waitFor([&] { return image && info; }, 5.0));
  const Letterbox box = PixelOracle(info_, kDemoMount)
                            .box(projector_->outputWindow()->width(), projector_->outputWindow()->height());
  EXPECT_EQ(int(image->width), box.width);
  EXPECT_EQ(int(image->height), box.height);
  EXPECT_EQ(image->encoding, "rgb8");
  EXPECT_EQ(image->header.frame_id, kOpticalFrame);
  // The CameraInfo describes the published image (scaled with it), not the projector's panel.
  EXPECT_EQ(info->width, image->width);
  EXPECT_EQ(info->height, image->height);
  int magenta = 0;
  for (std::size_t i = 0; i + 2 < image->data.size(); i += 3)
  {
    magenta += (image->data[i] > 200 && image->data[i + 1] < 60 && image->data[i + 2] > 200) ? 1 : 0;
  }
  EXPECT_GT(magenta, 100) << "the published image shows the arrows";
  // Off again: nothing more is published.
  projector_->subProp("Image output")->setValue(false);
  ASSERT_TRUE(waitFor([&] { return image_sub.getNumPublishers() == 0; })) << "the publisher is gone";
  ros::spinOnce();  // what was sent before
  image.reset();
  EXPECT_FALSE(waitFor([&] { return bool(image); }, 0.5)) << "published after Image output was turned off";
}

TEST_F(ProjectorCameraTest, EscapeLeavesFullScreen)
{
  if (QGuiApplication::screens().size() < 2)
  {
    GTEST_SKIP() << "full screen needs a second screen (scripts/test starts a two-screen X server)";
  }
  info_pub_.publish(cameraInfo(1280, 800, 1300, 639.5, 399.5));
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isFullScreenOn(); }));
  EXPECT_EQ(projector_->outputWindow()->cursor().shape(), Qt::BlankCursor) << "no mouse cursor on the floor";
  QKeyEvent escape(QEvent::KeyPress, Qt::Key_Escape, Qt::NoModifier);
  QApplication::sendEvent(projector_->outputWindow(), &escape);
  ASSERT_TRUE(waitFor([&] { return !projector_->outputWindow()->isFullScreenOn(); }));
  EXPECT_EQ(projector_->subProp("Full screen")->getValue().toBool(), false);
  EXPECT_EQ(visibleProjectorWindows(), 1);
}

TEST_F(ProjectorSceneTest, AntiAliasingIsOffByDefaultAndCanBeTurnedOn)
{
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  EXPECT_EQ(projector_->outputWindow()->fsaa(), 0);
  EXPECT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100);
  projector_->subProp("Anti-aliasing")->setValue(true);
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->fsaa() == 4; }));
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow()->isVisible(); }));
  EXPECT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100) << "renders with multisampling too";
  EXPECT_EQ(visibleProjectorWindows(), 1);
}
