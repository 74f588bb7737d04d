// ProjectorCamera in a real rviz: created through pluginlib, fed CameraInfo and tf, checked by the
// pixels of its output window against the pinhole model, and by its statuses.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <QGuiApplication>
#include <QImage>
#include <QScreen>
#include <QWindow>
#include <nav_msgs/Path.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>
#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/disc_outline.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_test_fixture.h"

using rviz_projector::PinholeModel;
using rviz_projector::ProjectorCameraDisplay;
using rviz_projector::RigidTransform;
using rviz_projector::Vec2;
using rviz_projector::Vec3;
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
  sensor_msgs::CameraInfo info;
  info.header.frame_id = kOpticalFrame;
  info.width = w;
  info.height = h;
  info.distortion_model = "plumb_bob";
  info.D = {0, 0, 0, 0, 0};
  info.K = {f, 0, cx, 0, f, cy, 0, 0, 1};
  info.R = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  info.P = {f, 0, cx, 0, 0, f, cy, 0, 0, 0, 1, 0};
  return info;
}

/// Quaternion (x, y, z, w) of roll-pitch-yaw about fixed x, y, z (as tf's setRPY).
void rpy(double roll, double pitch, double yaw, double q[4])
{
  const double cr = std::cos(roll / 2), sr = std::sin(roll / 2), cp = std::cos(pitch / 2), sp = std::sin(pitch / 2);
  const double cy = std::cos(yaw / 2), sy = std::sin(yaw / 2);
  q[0] = sr * cp * cy - cr * sp * sy;
  q[1] = cr * sp * cy + sr * cp * sy;
  q[2] = cr * cp * sy - sr * sp * cy;
  q[3] = cr * cp * cy + sr * sp * sy;
}

/// Hamilton product a * b of (x, y, z, w) quaternions.
void multiply(const double a[4], const double b[4], double out[4])
{
  out[0] = a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1];
  out[1] = a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0];
  out[2] = a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3];
  out[3] = a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2];
}

/// Optical frame of a projector body at `position` (x forward, z up) with roll/pitch/yaw.
Mount bodyMount(const Vec3& position, double roll, double pitch, double yaw)
{
  double body[4], optical[4];
  rpy(roll, pitch, yaw, body);
  const double body_to_optical[4] = {-0.5, 0.5, -0.5, 0.5};
  multiply(body, body_to_optical, optical);
  return Mount{position, optical[0], optical[1], optical[2], optical[3]};
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
    EXPECT_EQ(image.width(), int(info.width));
    EXPECT_EQ(image.height(), int(info.height));
    double worst = 0.0;
    for (std::size_t i = 0; i < pixels.size(); ++i)
    {
      const Vec2 floor = floorPointAt(lens, m, pixels[i]);
      const Vec2 centre = pixelOf(lens, m, floor);
      const Vec2 expected = projectedDiscCentroid(lens, m, floor, diameters[i]);
      Vec2 centroid;
      int count = 0;
      const bool found = greenCentroid(image, expected, 60, centroid, count);
      EXPECT_TRUE(found) << "target " << i << " not seen near " << expected.x << "," << expected.y;
      if (!found)
      {
        worst = std::numeric_limits<double>::infinity();
        continue;
      }
      const double error = std::hypot(centroid.x - expected.x, centroid.y - expected.y);
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
