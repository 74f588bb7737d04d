// ProjectorCamera in a real rviz: created through pluginlib, fed CameraInfo and tf, checked by the
// pixels of its output window against the pinhole model, and by its statuses.
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
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/render_panel.h>
#include <rviz/visualization_manager.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "rviz_projector/core/disc_outline.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/displays/main_view_cost.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "optical_orientation.h"
#include "rviz_test_fixture.h"

using rviz_projector::PinholeModel;
using rviz_projector::ProjectorCameraDisplay;
using rviz_projector::RigidTransform;
using rviz_projector::Vec2;
using rviz_projector::Vec3;
using rviz_projector_test::countColour;
using rviz_projector_test::Status;

namespace
{
constexpr const char* kInfoTopic = "/test/projector/camera_info";
constexpr const char* kOpticalFrame = "test_projector_optical";

struct Mount
{
  Vec3 position;
  double qx, qy, qz, qw;  // optical frame orientation in map
};

sensor_msgs::CameraInfo cameraInfo(unsigned w, unsigned h, double f, double cx, double cy)
{
  return rviz_projector_test::cameraInfo(kOpticalFrame, w, h, f, cx, cy);
}

/// Quaternion (x, y, z, w) of roll-pitch-yaw about fixed x, y, z (as tf's setRPY).
/// Optical frame of a projector body at `position` (x forward, z up) with roll/pitch/yaw.
Mount bodyMount(const Vec3& position, double roll, double pitch, double yaw)
{
  const rviz_projector_test::Quaternion q = rviz_projector_test::opticalOrientation(roll, pitch, yaw);
  return Mount{position, q.x, q.y, q.z, q.w};
}

/// Floor point (z = 0) seen at `pixel`.
Vec2 floorPointAt(const PinholeModel& lens, const Mount& m, const Vec2& pixel)
{
  const RigidTransform pose = RigidTransform::fromQuaternion(m.qx, m.qy, m.qz, m.qw, m.position);
  const Vec3 d = pose.rotate(lens.ray(pixel));
  const double t = -m.position.z / d.z;
  return Vec2{m.position.x + t * d.x, m.position.y + t * d.y};
}

/// Pixel of a floor point, by the pinhole model.
Vec2 pixelOf(const PinholeModel& lens, const Mount& m, const Vec2& floor)
{
  const RigidTransform pose = RigidTransform::fromQuaternion(m.qx, m.qy, m.qz, m.qw, m.position);
  const auto& R = pose.rotation();
  const Vec3 d = Vec3{floor.x, floor.y, 0.0} - m.position;
  const Vec3 optical{R[0] * d.x + R[3] * d.y + R[6] * d.z, R[1] * d.x + R[4] * d.y + R[7] * d.z,
                     R[2] * d.x + R[5] * d.y + R[8] * d.z};
  Vec2 px;
  EXPECT_TRUE(lens.project(optical, px));
  return px;
}

/// Depth (optical z) of a floor point.
double depthOf(const Mount& m, const Vec2& floor)
{
  const RigidTransform pose = RigidTransform::fromQuaternion(m.qx, m.qy, m.qz, m.qw, m.position);
  const auto& R = pose.rotation();
  const Vec3 d = Vec3{floor.x, floor.y, 0.0} - m.position;
  return R[2] * d.x + R[5] * d.y + R[8] * d.z;
}

/// Where the pinhole model puts the centroid of a floor disc: the area centroid of its projected
/// outline (a disc seen at an angle is not centred on its centre's projection).
Vec2 projectedDiscCentroid(const PinholeModel& lens, const Mount& m, const Vec2& centre, double diameter)
{
  std::vector<Vec2> triangles;
  rviz_projector::DiscOutline(centre, diameter).appendTriangles(triangles);
  double sx = 0, sy = 0, sa = 0;
  for (std::size_t i = 0; i < triangles.size(); i += 3)
  {
    const Vec2 a = pixelOf(lens, m, triangles[i]), b = pixelOf(lens, m, triangles[i + 1]),
               c = pixelOf(lens, m, triangles[i + 2]);
    const double area = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    sx += area * (a.x + b.x + c.x) / 3;
    sy += area * (a.y + b.y + c.y) / 3;
    sa += area;
  }
  return Vec2{sx / sa, sy / sa};
}

/// Centroid (pixel-centre coordinates) of the green pixels within `radius` of `around`.
bool greenCentroid(const QImage& image, const Vec2& around, int radius, Vec2& centroid, int& count)
{
  double sx = 0, sy = 0, sw = 0;
  count = 0;
  for (int y = std::max(0, int(around.y) - radius); y <= std::min(image.height() - 1, int(around.y) + radius); ++y)
  {
    for (int x = std::max(0, int(around.x) - radius); x <= std::min(image.width() - 1, int(around.x) + radius); ++x)
    {
      const QRgb c = image.pixel(x, y);
      if (qGreen(c) > 128 && qRed(c) < 100 && qBlue(c) < 100)
      {
        const double w = qGreen(c) / 255.0;
        sx += w * x;
        sy += w * y;
        sw += w;
        ++count;
      }
    }
  }
  if (sw <= 0)
  {
    return false;
  }
  centroid = Vec2{sx / sw, sy / sw};
  return true;
}

class ProjectorCameraTest : public rviz_projector_test::RvizTest
{
protected:
  void SetUp() override
  {
    RvizTest::SetUp();
    info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>(kInfoTopic, 1, true);
    rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectorCamera", "Projector");
    projector_ = dynamic_cast<ProjectorCameraDisplay*>(d);
    ASSERT_NE(projector_, nullptr) << "pluginlib did not give a ProjectorCameraDisplay";
    projector_->subProp("Topic")->setValue(kInfoTopic);
    projector_->subProp("Footprint in main view")->setValue(true);
  }

  void mount(const Mount& m)
  {
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = "map";
    t.child_frame_id = kOpticalFrame;
    t.transform.translation.x = m.position.x;
    t.transform.translation.y = m.position.y;
    t.transform.translation.z = m.position.z;
    t.transform.rotation.x = m.qx;
    t.transform.rotation.y = m.qy;
    t.transform.rotation.z = m.qz;
    t.transform.rotation.w = m.qw;
    static_tf_->sendTransform(t);
  }

  /// A ProjectedPath with a single pose: just its destination disc, a target on the floor.
  void addTarget(const Vec2& p, double diameter)
  {
    const std::string topic = "/test/target" + std::to_string(targets_.size());
    rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectedPath", QString::fromStdString(topic));
    d->subProp("Topic")->setValue(QString::fromStdString(topic));
    d->subProp("Destination circle diameter")->setValue(diameter);
    d->subProp("Height above floor")->setValue(0.0);
    ros::Publisher pub = nh_.advertise<nav_msgs::Path>(topic, 1, true);
    nav_msgs::Path path;
    path.header.frame_id = "map";
    geometry_msgs::PoseStamped pose;
    pose.header = path.header;
    pose.pose.position.x = p.x;
    pose.pose.position.y = p.y;
    pose.pose.orientation.w = 1;
    path.poses.push_back(pose);
    pub.publish(path);
    target_pubs_.push_back(pub);
    targets_.push_back(dynamic_cast<rviz_projector::ProjectedPathDisplay*>(d));
  }

  bool targetsReady()
  {
    for (auto* t : targets_)
    {
      if (!t || !t->spacedPath().has_destination)
      {
        return false;
      }
    }
    return true;
  }

  /// Renders a frame and reads the output window's pixels back from the X server: exactly what the
  /// projector shows. (OGRE's own read-back of the back buffer is off by a fraction of a pixel on
  /// Mesa's software GL, so it is not used to judge accuracy.)
  QImage grab()
  {
    rviz_projector::ProjectorOutputWindow* window = projector_->outputWindow();
    if (!window)
    {
      return QImage();
    }
    projector_->renderNow();
    spinFor(0.1);
    QScreen* screen = window->windowHandle() ? window->windowHandle()->screen() : QGuiApplication::primaryScreen();
    QImage copy = screen->grabWindow(window->winId()).toImage().convertToFormat(QImage::Format_RGB888);
    if (const char* dir = std::getenv("RVIZ_PROJECTOR_TEST_IMAGES"))
    {
      copy.save(QString("%1/%2-%3.png")
                    .arg(dir)
                    .arg(::testing::UnitTest::GetInstance()->current_test_info()->name())
                    .arg(grabs_++));
    }
    return copy;
  }

  /// Window pixels of the projector image: the image minus the letterbox offset.
  QImage imagePart(const QImage& window)
  {
    int left, top, width, height;
    projector_->viewportPixels(left, top, width, height);
    return window.copy(left, top, width, height);
  }

  /// Runs the pixel-accuracy check for one projector set-up; returns the largest error. Targets
  /// are floor discs about kTargetPixels across in the image, centred on the floor points seen at
  /// `pixels`.
  double pixelAccuracy(const sensor_msgs::CameraInfo& info, const Mount& m, const std::vector<Vec2>& pixels)
  {
    constexpr double kTargetPixels = 36.0;
    PinholeModel lens;
    EXPECT_TRUE(PinholeModel::fromCalibration(rviz_projector_test_lens(info), lens).ok());
    mount(m);
    std::vector<double> diameters;
    for (const Vec2& px : pixels)
    {
      const Vec2 floor = floorPointAt(lens, m, px);
      diameters.push_back(kTargetPixels * depthOf(m, floor) / lens.fx());
      addTarget(floor, diameters.back());
    }
    info_pub_.publish(info);
    EXPECT_TRUE(waitFor([&] { return projector_->hasLens() && targetsReady(); }));
    EXPECT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
    spinFor(0.5);
    const QImage image = imagePart(grab());
    // The image fills the window (letterboxed when the aspect ratios differ): scale the pinhole
    // prediction from image pixels to window pixels, report errors in image pixels.
    const double sx = double(image.width()) / info.width;
    const double sy = double(image.height()) / info.height;
    EXPECT_NEAR(sx, sy, 0.01) << "never stretched";
    auto toWindow = [sx, sy](const Vec2& p) { return Vec2{(p.x + 0.5) * sx - 0.5, (p.y + 0.5) * sy - 0.5}; };
    std::printf("  image %ux%u shown as %dx%d\n", info.width, info.height, image.width(), image.height());
    double worst = 0.0;
    for (std::size_t i = 0; i < pixels.size(); ++i)
    {
      const Vec2 floor = floorPointAt(lens, m, pixels[i]);
      const Vec2 centre = pixelOf(lens, m, floor);
      const Vec2 expected = toWindow(projectedDiscCentroid(lens, m, floor, diameters[i]));
      Vec2 centroid;
      int count = 0;
      const bool found = greenCentroid(image, expected, 60, centroid, count);
      EXPECT_TRUE(found) << "target " << i << " not seen near " << expected.x << "," << expected.y;
      if (!found)
      {
        worst = std::numeric_limits<double>::infinity();
        continue;
      }
      const double error = std::hypot((centroid.x - expected.x) / sx, (centroid.y - expected.y) / sy);
      std::printf("  target %zu: centre projects to (%.3f, %.3f), disc centroid (%.3f, %.3f), rendered "
                  "(%.3f, %.3f) from %d px: error %.3f px\n",
                  i, centre.x, centre.y, expected.x, expected.y, centroid.x, centroid.y, count, error);
      worst = std::max(worst, error);
    }
    return worst;
  }

  static rviz_projector::LensCalibration rviz_projector_test_lens(const sensor_msgs::CameraInfo& info)
  {
    rviz_projector::LensCalibration c;
    c.width = info.width;
    c.height = info.height;
    std::copy(info.K.begin(), info.K.end(), c.K.begin());
    std::copy(info.P.begin(), info.P.end(), c.P.begin());
    return c;
  }

  ros::Publisher info_pub_;
  ProjectorCameraDisplay* projector_ = nullptr;
  std::vector<ros::Publisher> target_pubs_;
  std::vector<rviz_projector::ProjectedPathDisplay*> targets_;
  int grabs_ = 0;
};
}  // namespace

TEST_F(ProjectorCameraTest, PixelAccuracyCentredLensLookingDown)
{
  const Mount down{{0.3, -0.2, 2.0}, 1.0, 0.0, 0.0, 0.0};  // optical z = -world z
  const double worst = pixelAccuracy(cameraInfo(1280, 800, 1000, 639.5, 399.5), down,
                                     {{640, 400}, {100.25, 80.5}, {1180, 90}, {1200.7, 730.2}, {70, 700}});
  std::printf("centred lens: max error %.3f px\n", worst);
  EXPECT_LE(worst, 0.25);
}

TEST_F(ProjectorCameraTest, PixelAccuracyReferenceProjectorOffAxis)
{
  // ViewSonic PA503W as calibrated in the reference set-up: cy = 817, beyond the bottom edge.
  const Mount m = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.6, 0.0);
  const double worst = pixelAccuracy(cameraInfo(1280, 800, 1900, 640, 817), m,
                                     {{640, 400}, {60, 40}, {1220, 50}, {1230, 760}, {50, 770}});
  std::printf("reference projector: max error %.3f px\n", worst);
  EXPECT_LE(worst, 0.25);
}

TEST_F(ProjectorCameraTest, PixelAccuracyRolledAndYawedMount)
{
  const Mount m = bodyMount({1.0, 2.0, 1.5}, 0.15, 0.8, 0.7);
  const double worst = pixelAccuracy(cameraInfo(1024, 768, 900, 530.3, 360.8), m,
                                     {{512, 384}, {50, 50}, {980, 60}, {990, 720}, {40, 730}});
  std::printf("rolled and yawed mount: max error %.3f px\n", worst);
  EXPECT_LE(worst, 0.25);
}

namespace
{
const QRgb kBlack = qRgb(0, 0, 0);
const QRgb kArrowMagenta = qRgb(255, 0, 255);

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

/// A demo-like set-up: 1280x800 projector 1.2 m up, pitched down 0.9 rad, looking along +x.
const Mount kDemoMount = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.9, 0.0);
}  // namespace

class ProjectorSceneTest : public ProjectorCameraTest
{
protected:
  void SetUp() override
  {
    ProjectorCameraTest::SetUp();
    ASSERT_TRUE(PinholeModel::fromCalibration(rviz_projector_test_lens(info_), lens_).ok());
    mount(kDemoMount);
    info_pub_.publish(info_);
    ASSERT_TRUE(waitFor([&] { return projector_->hasLens(); }));
    ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
  }

  rviz_projector::ProjectedPathDisplay* addPath(const std::string& topic, const std::vector<Vec2>& points)
  {
    rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectedPath", "Projected path");
    d->subProp("Topic")->setValue(QString::fromStdString(topic));
    path_pub_ = nh_.advertise<nav_msgs::Path>(topic, 1, true);
    nav_msgs::Path path;
    path.header.frame_id = "map";
    for (const Vec2& p : points)
    {
      geometry_msgs::PoseStamped pose;
      pose.header = path.header;
      pose.pose.position.x = p.x;
      pose.pose.position.y = p.y;
      pose.pose.orientation.w = 1;
      path.poses.push_back(pose);
    }
    path_pub_.publish(path);
    auto* display = dynamic_cast<rviz_projector::ProjectedPathDisplay*>(d);
    EXPECT_TRUE(waitFor([&] { return display && !display->spacedPath().arrows.empty(); }));
    return display;
  }

  /// Where the pinhole model puts a floor point in the (possibly scaled) projector image.
  Vec2 windowPixel(const Vec2& floor, const Mount& m = kDemoMount)
  {
    int left, top, width, height;
    projector_->viewportPixels(left, top, width, height);
    const Vec2 px = pixelOf(lens_, m, floor);
    return Vec2{(px.x + 0.5) * width / lens_.width() - 0.5, (px.y + 0.5) * height / lens_.height() - 0.5};
  }

  sensor_msgs::CameraInfo info_ = cameraInfo(1280, 800, 1300, 639.5, 399.5);
  PinholeModel lens_;
  ros::Publisher path_pub_;
};

TEST_F(ProjectorSceneTest, ArrowsReachTheProjectorAndVisibilityHidesThem)
{
  std::vector<Vec2> points;
  for (double x = 0.5; x <= 2.3; x += 0.037)
  {
    points.push_back({x, 0.05 * std::sin(2 * x)});
  }
  auto* path = addPath("/test/plan", points);
  ASSERT_NE(path, nullptr);
  spinFor(0.3);
  const QImage frame = imagePart(grab());
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
  const QImage hidden = imagePart(grab());
  EXPECT_EQ(countColour(hidden, kArrowMagenta), 0);
  EXPECT_EQ(countColour(hidden, kBlack), hidden.width() * hidden.height());
}

TEST_F(ProjectorSceneTest, OnlyThisPackagesPathDisplaysAreVisibleByDefault)
{
  rviz_->addDisplay("rviz/Grid", "Grid");
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  rviz::Property* visibility = projector_->subProp("Visibility");
  EXPECT_EQ(visibility->subProp("Grid")->getValue().toBool(), false);
  EXPECT_EQ(visibility->subProp("Projected path")->getValue().toBool(), true);
  // The grid lies on the floor in the projector's view; it must not be projected.
  rviz::Display* grid = nullptr;
  for (int i = 0; i < rviz_->manager()->getRootDisplayGroup()->numDisplays(); ++i)
  {
    if (rviz_->manager()->getRootDisplayGroup()->getDisplayAt(i)->getName() == "Grid")
    {
      grid = rviz_->manager()->getRootDisplayGroup()->getDisplayAt(i);
    }
  }
  ASSERT_NE(grid, nullptr);
  grid->subProp("Color")->setValue(QColor(255, 255, 0));
  const QImage frame = imagePart(grab());
  EXPECT_EQ(countColour(frame, qRgb(255, 255, 0)), 0);
}

TEST_F(ProjectorSceneTest, MovingProjectorKeepsAWorldTargetOnItsProjection)
{
  addTarget({1.2, 0.1}, 0.03);
  ASSERT_TRUE(waitFor([&] { return targetsReady(); }));
  for (double dx : {0.0, 0.07, -0.05})
  {
    Mount moved = kDemoMount;
    moved.position.x += dx;
    mount(moved);
    spinFor(0.2);
    const QImage frame = imagePart(grab());
    const Vec2 expected = windowPixel({1.2, 0.1}, moved);
    Vec2 centroid;
    int count = 0;
    ASSERT_TRUE(greenCentroid(frame, expected, 40, centroid, count)) << "dx " << dx;
    EXPECT_NEAR(centroid.x, expected.x, 1.0) << "dx " << dx;
    EXPECT_NEAR(centroid.y, expected.y, 1.0) << "dx " << dx;
  }
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
    const QImage frame = imagePart(grab());
    EXPECT_EQ(countColour(frame, kBlack), frame.width() * frame.height()) << c.what << ": background only";
    EXPECT_FALSE(rviz_->renderMainView().isNull()) << "rviz keeps rendering";
    info_pub_.publish(info_);  // good again
    ASSERT_TRUE(waitFor([&] { return projector_->hasLens(); })) << c.what;
  }
  // P all zero falls back to K, with the same picture.
  sensor_msgs::CameraInfo k_only = info_;
  k_only.P.fill(0);
  info_pub_.publish(k_only);
  spinFor(0.3);
  EXPECT_TRUE(projector_->hasLens());
  EXPECT_EQ(statusOf(projector_, "CameraInfo").level, rviz::StatusProperty::Ok);
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100);

  // Distortion is reported, not applied.
  sensor_msgs::CameraInfo distorted = info_;
  distorted.D = {0.1, -0.05, 0, 0, 0};
  info_pub_.publish(distorted);
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Distortion").present; }));
  EXPECT_EQ(statusOf(projector_, "Distortion").level, rviz::StatusProperty::Warn);
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
  const QImage frame = imagePart(grab());
  EXPECT_EQ(countColour(frame, kBlack), frame.width() * frame.height());
  // The Frame property overrides the header's frame.
  projector_->subProp("Frame")->setValue(kOpticalFrame);
  const QImage fixed = imagePart(grab());
  EXPECT_GT(countColour(fixed, kArrowMagenta), 100);
  EXPECT_EQ(statusOf(projector_, "Transform").level, rviz::StatusProperty::Ok);
}

TEST_F(ProjectorSceneTest, StaleCameraInfoStampStillRenders)
{
  addPath("/test/plan", {{0.5, 0.0}, {2.0, 0.0}});
  sensor_msgs::CameraInfo old = info_;
  old.header.stamp = ros::Time(1.0);  // far in the past, as a latched CameraInfo often is
  info_pub_.publish(old);
  spinFor(0.3);
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100);
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
  spinFor(0.2);
  projector_->renderNow();
  EXPECT_EQ(statusOf(projector_, "Footprint").level, rviz::StatusProperty::Warn);
}

TEST_F(ProjectorSceneTest, TestPatternDrawsAMetricGrid)
{
  projector_->subProp("Test pattern")->setValue(true);
  projector_->renderNow();
  const QImage frame = imagePart(grab());
  // Bold metre line x = 1 m across the floor: white at its projection.
  const Vec2 on_line = windowPixel({1.0, 0.0});
  Vec2 off_line = windowPixel({1.05, 0.03});
  EXPECT_TRUE(rviz_projector_test::sameColour(frame.pixel(int(std::lround(on_line.x)), int(std::lround(on_line.y))),
                                              qRgb(255, 255, 255), 30));
  EXPECT_EQ(frame.pixel(int(std::lround(off_line.x)), int(std::lround(off_line.y))), kBlack);
  EXPECT_GT(countColour(frame, qRgb(255, 255, 255)), 2000);
  projector_->subProp("Test pattern")->setValue(false);
  EXPECT_EQ(countColour(imagePart(grab()), qRgb(255, 255, 255)), 0);
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
  spinFor(0.2);
  EXPECT_EQ(visibleProjectorWindows(), 1);
  delete projector_;
  projector_ = nullptr;
  spinFor(0.2);
  EXPECT_EQ(visibleProjectorWindows(), 0);
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
  int left, top, width, height;
  projector_->viewportPixels(left, top, width, height);
  EXPECT_EQ(width, 1280);
  EXPECT_EQ(height, 800);  // 1:1 on a 1280x800 screen

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
  pumpQt(0.3);
  rviz_projector::ProjectorOutputWindow* window = projector_->outputWindow();
  ASSERT_GT(countColour(peek(window), kArrowMagenta), 100);

  // Nothing changes: no new frames.
  const std::uint64_t rendered = projector_->framesRendered();
  const std::uint64_t skipped = projector_->framesSkipped();
  pumpQt(0.5);
  EXPECT_EQ(projector_->framesRendered(), rendered) << "re-rendered an unchanged view";
  EXPECT_GT(projector_->framesSkipped(), skipped);

  // A new path (arrows elsewhere) reaches the window through the projector's own timer.
  nav_msgs::Path moved;
  moved.header.frame_id = "map";
  for (double x : {0.5, 2.0})
  {
    geometry_msgs::PoseStamped pose;
    pose.header = moved.header;
    pose.pose.position.x = x;
    pose.pose.position.y = 0.15;
    pose.pose.orientation.w = 1;
    moved.poses.push_back(pose);
  }
  path_pub_.publish(moved);
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
    int left, top, width, height;
    projector_->viewportPixels(left, top, width, height);
    arrived = rviz_projector_test::sameColour(
        frame.pixel(left + int(std::lround(new_arrow.x)), top + int(std::lround(new_arrow.y))), kArrowMagenta, 30);
  }
  EXPECT_TRUE(arrived) << "the new path never reached the projector window";
  EXPECT_GT(projector_->framesRendered(), rendered);
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
  int left, top, width, height;
  projector_->viewportPixels(left, top, width, height);
  EXPECT_EQ(int(image->width), width);
  EXPECT_EQ(int(image->height), height);
  EXPECT_EQ(image->encoding, "rgb8");
  EXPECT_EQ(image->header.frame_id, kOpticalFrame);
  EXPECT_EQ(info->width, 1280u);
  int magenta = 0;
  for (std::size_t i = 0; i + 2 < image->data.size(); i += 3)
  {
    magenta += (image->data[i] > 200 && image->data[i + 1] < 60 && image->data[i + 2] > 200) ? 1 : 0;
  }
  EXPECT_GT(magenta, 100) << "the published image shows the arrows";
  // Off again: nothing more is published.
  projector_->subProp("Image output")->setValue(false);
  spinFor(0.2);
  image.reset();
  spinFor(0.5);
  EXPECT_FALSE(image);
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
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100);
  projector_->subProp("Anti-aliasing")->setValue(true);
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->fsaa() == 4; }));
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow()->isVisible(); }));
  spinFor(0.2);
  EXPECT_GT(countColour(imagePart(grab()), kArrowMagenta), 100) << "renders with multisampling too";
  EXPECT_EQ(visibleProjectorWindows(), 1);
}
