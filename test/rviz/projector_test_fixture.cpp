#include "projector_test_fixture.h"
#include "robustness_helpers.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <opencv2/calib3d.hpp>

#include <QApplication>
#include <QGuiApplication>
#include <QScreen>
#include <QWindow>
#include <nav_msgs/Path.h>
#include <rviz/display.h>

#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"

namespace rviz_projector_test
{
Mount bodyMount(const Vec3& position, double roll, double pitch, double yaw)
{
  const Quaternion q = opticalOrientation(roll, pitch, yaw);
  return Mount{position, q.x, q.y, q.z, q.w};
}

const Mount kDemoMount = bodyMount({0.0, 0.0, 1.2}, 0.0, 0.9, 0.0);

sensor_msgs::CameraInfo projectorInfo(unsigned w, unsigned h, double f, double cx, double cy)
{
  return cameraInfo(kOpticalFrame, w, h, f, cx, cy);
}

sensor_msgs::CameraInfo distortedInfo(const std::vector<double>& d)
{
  sensor_msgs::CameraInfo info = projectorInfo(1280, 800, 1900, 639.5, 399.5);
  info.distortion_model = "plumb_bob";
  info.D = d;
  return info;
}

Letterbox letterbox(int ww, int wh, int iw, int ih)
{
  Letterbox box;
  if (iw <= ww && ih <= wh && (iw == ww || ih == wh))
  {
    box.width = iw;
    box.height = ih;
  }
  else
  {
    const double scale = std::min(double(ww) / iw, double(wh) / ih);
    box.width = std::max(1, int(std::lround(iw * scale)));
    box.height = std::max(1, int(std::lround(ih * scale)));
  }
  box.left = (ww - box.width) / 2;
  box.top = (wh - box.height) / 2;
  return box;
}

PixelOracle::PixelOracle(const sensor_msgs::CameraInfo& info, const Mount& mount)
{
  EXPECT_TRUE(model_.fromCameraInfo(info)) << "image_geometry takes the CameraInfo";
  pose_ = tf2::Transform(tf2::Quaternion(mount.qx, mount.qy, mount.qz, mount.qw),
                         tf2::Vector3(mount.position.x, mount.position.y, mount.position.z));
  // By hand from the fields: the ROI (all zero: the whole sensor), then the binning (0 means 1).
  const bool roi = info.roi.width > 0 && info.roi.height > 0;
  const unsigned bx = std::max(1u, info.binning_x), by = std::max(1u, info.binning_y);
  width_ = int((roi ? info.roi.width : info.width) / bx);
  height_ = int((roi ? info.roi.height : info.height) / by);
  d_.assign(info.D.begin(), info.D.end());
  distorted_ = std::any_of(d_.begin(), d_.end(), [](double d) { return d != 0.0; });
  const double ox = roi ? info.roi.x_offset : 0.0, oy = roi ? info.roi.y_offset : 0.0;
  raw_k_ = cv::Matx33d(info.K[0] / bx, 0.0, (info.K[2] - ox) / bx, 0.0, info.K[4] / by, (info.K[5] - oy) / by, 0.0, 0.0,
                       1.0);
}

cv::Point3d PixelOracle::optical(const Vec2& floor) const
{
  const tf2::Vector3 p = pose_.inverse() * tf2::Vector3(floor.x, floor.y, 0.0);
  return cv::Point3d(p.x(), p.y(), p.z());
}

Vec2 PixelOracle::imagePixel(const Vec2& floor) const
{
  if (distorted_)
  {
    std::vector<cv::Point2d> uv;
    cv::projectPoints(std::vector<cv::Point3d>{optical(floor)}, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), raw_k_, d_, uv);
    return Vec2{uv[0].x, uv[0].y};
  }
  const cv::Point2d uv = model_.project3dToPixel(optical(floor));
  return Vec2{uv.x, uv.y};
}

Vec2 PixelOracle::floorPoint(const Vec2& pixel) const
{
  cv::Point3d ray = model_.projectPixelTo3dRay(cv::Point2d(pixel.x, pixel.y));
  if (distorted_)
  {
    std::vector<cv::Point2d> normalised;
    cv::undistortPoints(std::vector<cv::Point2d>{cv::Point2d(pixel.x, pixel.y)}, normalised, raw_k_, d_, cv::noArray(),
                        cv::noArray(), cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 100, 1e-12));
    ray = cv::Point3d(normalised[0].x, normalised[0].y, 1.0);
  }
  const tf2::Vector3 d = pose_.getBasis() * tf2::Vector3(ray.x, ray.y, ray.z);
  const tf2::Vector3& o = pose_.getOrigin();
  const double t = -o.z() / d.z();
  return Vec2{o.x() + t * d.x(), o.y() + t * d.y()};
}

double PixelOracle::depth(const Vec2& floor) const
{
  return optical(floor).z;
}

Vec2 PixelOracle::discCentroid(const Vec2& centre, double diameter, double* area) const
{
  // The outline as a fine polygon, projected; its area centroid (shoelace).
  constexpr int kSegments = 720;
  std::vector<Vec2> outline;
  for (int i = 0; i < kSegments; ++i)
  {
    const double a = 2.0 * M_PI * i / kSegments;
    outline.push_back(imagePixel(centre + Vec2{std::cos(a), std::sin(a)} * (diameter / 2)));
  }
  double sx = 0, sy = 0, sa = 0;
  for (int i = 0; i < kSegments; ++i)
  {
    const Vec2& a = outline[i];
    const Vec2& b = outline[(i + 1) % kSegments];
    const double cross = a.x * b.y - b.x * a.y;
    sa += cross;
    sx += (a.x + b.x) * cross;
    sy += (a.y + b.y) * cross;
  }
  if (area)
  {
    *area = std::abs(sa) / 2;
  }
  return Vec2{sx / (3 * sa), sy / (3 * sa)};
}

Vec2 PixelOracle::toWindow(const Letterbox& box, const Vec2& p) const
{
  // Pixel centres at integers in both: the image's edge u = -0.5 lands on the box's edge.
  return Vec2{box.left + (p.x + 0.5) * box.width / width_ - 0.5, box.top + (p.y + 0.5) * box.height / height_ - 0.5};
}

bool greenCentroid(const QImage& image, const Vec2& around, int radius, Vec2& centroid, int& count)
{
  double sx = 0, sy = 0, sw = 0;
  count = 0;
  if (!std::isfinite(around.x) || !std::isfinite(around.y))
  {
    return false;
  }
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

void saveShot(const QImage& image, const char* name)
{
  if (const char* folder = std::getenv("RP_TEST_SHOTS"))
  {
    image.save(QString("%1/%2.png").arg(folder, name));
  }
}

std::vector<Vec2> lineAlongX(double from, double to)
{
  std::vector<Vec2> points;
  for (double x = from; x < to - 1e-9; x += 0.05)
  {
    points.push_back({x, 0.0});
  }
  points.push_back({to, 0.0});
  return points;
}

Letterbox litBounds(const QImage& image)
{
  int first_x = -1, last_x = -1, first_y = -1, last_y = -1;
  for (int y = 0; y < image.height(); ++y)
  {
    for (int x = 0; x < image.width(); ++x)
    {
      const QRgb c = image.pixel(x, y);
      if (qRed(c) > 128 && qGreen(c) > 128 && qBlue(c) > 128)
      {
        first_x = first_x < 0 ? x : std::min(first_x, x);
        last_x = std::max(last_x, x);
        first_y = first_y < 0 ? y : first_y;
        last_y = y;
      }
    }
  }
  Letterbox lit;
  lit.left = first_x;
  lit.top = first_y;
  lit.width = first_x < 0 ? 0 : last_x - first_x + 1;
  lit.height = first_y < 0 ? 0 : last_y - first_y + 1;
  return lit;
}

void ProjectorCameraTest::SetUp()
{
  RvizTest::SetUp();
  info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>(kInfoTopic, 1, true);
  rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectorCamera", "Projector");
  projector_ = dynamic_cast<rviz_projector::ProjectorCameraDisplay*>(d);
  ASSERT_NE(projector_, nullptr) << "pluginlib did not give a ProjectorCameraDisplay";
  projector_->subProp("Topic")->setValue(kInfoTopic);
  projector_->subProp("Footprint in main view")->setValue(true);
}

void ProjectorCameraTest::mount(const Mount& m)
{
  static_tf_->sendTransform(
      stampedTransform("map", kOpticalFrame, m.position.x, m.position.y, m.position.z, {m.qx, m.qy, m.qz, m.qw}));
}

void ProjectorCameraTest::addTarget(const Vec2& p, double diameter)
{
  const std::string topic = "/test/target" + std::to_string(targets_.size());
  rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectedPath", QString::fromStdString(topic));
  d->subProp("Topic")->setValue(QString::fromStdString(topic));
  d->subProp("Destination circle diameter")->setValue(diameter);
  d->subProp("Height above floor")->setValue(0.0);
  target_pubs_.push_back(nh_.advertise<nav_msgs::Path>(topic, 1, true));
  targets_.push_back(dynamic_cast<rviz_projector::ProjectedPathDisplay*>(d));
  moveTarget(targets_.size() - 1, p);
}

void ProjectorCameraTest::moveTarget(std::size_t index, const Vec2& p)
{
  nav_msgs::Path path;
  path.header.frame_id = "map";
  geometry_msgs::PoseStamped pose;
  pose.header = path.header;
  pose.pose.position.x = p.x;
  pose.pose.position.y = p.y;
  pose.pose.orientation.w = 1;
  path.poses.push_back(pose);
  target_pubs_.at(index).publish(path);
}

bool ProjectorCameraTest::targetsReady() const
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

QImage ProjectorCameraTest::grab()
{
  rviz_projector::ProjectorOutputWindow* window = projector_->outputWindow();
  if (!window)
  {
    return QImage();
  }
  projector_->renderNow();
  QApplication::processEvents();
  syncWithTheXServer();  // the frame just swapped is on the server before Qt's connection reads it
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

QImage ProjectorCameraTest::grabWhen(const std::function<bool(const QImage&)>& ok, double timeout)
{
  QImage last = grab();
  QImage current = last;
  waitFor(
      [&] {
        current = grab();
        const bool settled = !current.isNull() && current == last;
        last = current;
        return settled && ok(current);
      },
      timeout);
  return current;
}

bool ProjectorCameraTest::waitForFrames(int frames, double timeout)
{
  const std::uint64_t start = projector_->framesRendered();
  return waitFor([&] { return projector_->framesRendered() >= start + std::uint64_t(frames); }, timeout);
}

QImage ProjectorCameraTest::imagePart(const QImage& window_image, const PixelOracle& oracle)
{
  const Letterbox box = oracle.box(window_image.width(), window_image.height());
  return window_image.copy(box.left, box.top, box.width, box.height);
}

double ProjectorCameraTest::pixelAccuracy(const sensor_msgs::CameraInfo& info, const Mount& m,
                                          const std::vector<Vec2>& pixels)
{
  constexpr double kTargetPixels = 36.0;
  const PixelOracle oracle(info, m);
  mount(m);
  std::vector<Vec2> floors;
  std::vector<double> diameters;
  for (const Vec2& px : pixels)
  {
    floors.push_back(oracle.floorPoint(px));
    diameters.push_back(kTargetPixels * oracle.depth(floors.back()) / oracle.fx());
    addTarget(floors.back(), diameters.back());
  }
  info_pub_.publish(info);
  EXPECT_TRUE(waitFor([&] { return projector_->hasLens() && targetsReady(); }));
  EXPECT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
  // Where the targets must be in a window of the grabbed size.
  auto expectedIn = [&](const QImage& window) {
    std::vector<Vec2> expected;
    const Letterbox box = oracle.box(window.width(), window.height());
    for (std::size_t i = 0; i < floors.size(); ++i)
    {
      expected.push_back(oracle.toWindow(box, oracle.discCentroid(floors[i], diameters[i])));
    }
    return expected;
  };
  // Every target shown (at least half of the window pixels its projected outline covers).
  auto allSeen = [&](const QImage& window) {
    const Letterbox box = oracle.box(window.width(), window.height());
    const double scale = double(box.width) / oracle.imageWidth();
    const std::vector<Vec2> expected = expectedIn(window);
    for (std::size_t i = 0; i < expected.size(); ++i)
    {
      double area = 0.0;
      oracle.discCentroid(floors[i], diameters[i], &area);
      Vec2 centroid;
      int count = 0;
      if (!greenCentroid(window, expected[i], int(2 * kTargetPixels * scale), centroid, count) ||
          count < 0.5 * area * scale * scale)
      {
        return false;
      }
    }
    return true;
  };
  const QImage window = grabWhen(allSeen);
  EXPECT_EQ(window.size(), projector_->outputWindow()->size()) << "grabbed the whole output window";
  const Letterbox box = oracle.box(window.width(), window.height());
  const double sx = double(box.width) / oracle.imageWidth();
  const double sy = double(box.height) / oracle.imageHeight();
  std::printf("  image %dx%d shown as %dx%d at %d,%d in a %dx%d window\n", oracle.imageWidth(), oracle.imageHeight(),
              box.width, box.height, box.left, box.top, window.width(), window.height());
  const std::vector<Vec2> expected = expectedIn(window);
  double worst = 0.0;
  for (std::size_t i = 0; i < expected.size(); ++i)
  {
    Vec2 centroid;
    int count = 0;
    const bool found = greenCentroid(window, expected[i], int(2 * kTargetPixels * sx), centroid, count);
    EXPECT_TRUE(found) << "target " << i << " not seen near " << expected[i].x << "," << expected[i].y;
    if (!found)
    {
      worst = std::numeric_limits<double>::infinity();
      continue;
    }
    const double dx = centroid.x - expected[i].x, dy = centroid.y - expected[i].y;
    // Window pixels land on the floor; image pixels are what the calibration speaks in.
    const double error = std::max(std::hypot(dx, dy), std::hypot(dx / sx, dy / sy));
    const Vec2 centre = oracle.imagePixel(floors[i]);
    std::printf("  target %zu: centre projects to image (%.3f, %.3f), disc centroid in the window (%.3f, %.3f), "
                "rendered (%.3f, %.3f) from %d px: error %.3f px\n",
                i, centre.x, centre.y, expected[i].x, expected[i].y, centroid.x, centroid.y, count, error);
    worst = std::max(worst, error);
  }
  return worst;
}

void ProjectorSceneTest::SetUp()
{
  ProjectorCameraTest::SetUp();
  mount(kDemoMount);
  info_pub_.publish(info_);
  ASSERT_TRUE(waitFor([&] { return projector_->hasLens(); }));
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
}

rviz_projector::ProjectedPathDisplay* ProjectorSceneTest::addPath(const std::string& topic,
                                                                  const std::vector<Vec2>& points)
{
  rviz::Display* d = rviz_->addDisplay("rviz_projector/ProjectedPath", "Projected path");
  d->subProp("Topic")->setValue(QString::fromStdString(topic));
  path_pub_ = nh_.advertise<nav_msgs::Path>(topic, 1, true);
  std::vector<Vec3> floor;
  for (const Vec2& p : points)
  {
    floor.push_back(Vec3{p.x, p.y, 0.0});
  }
  path_pub_.publish(makePath("map", floor));
  auto* display = dynamic_cast<rviz_projector::ProjectedPathDisplay*>(d);
  EXPECT_TRUE(waitFor([&] { return display && !display->spacedPath().arrows.empty(); }));
  return display;
}

rviz_projector::ProjectedPathDisplay* ProjectorSceneTest::addFloorPathFromRobot(const std::vector<Vec2>& points,
                                                                               double robot_x, double yaw)
{
  publishStaticTransform("map", "base_link", robot_x, 0.0, 0.0, yaw);
  rviz_projector::ProjectedPathDisplay* path = addPath("/test/plan", points);
  if (path != nullptr)
  {
    path->subProp("Height above floor")->setValue(0.0);
  }
  return path;
}

QImage ProjectorSceneTest::imagePart(const QImage& window) const
{
  return ProjectorCameraTest::imagePart(window, PixelOracle(info_, kDemoMount));
}

Vec2 ProjectorSceneTest::windowPixel(const Vec2& floor, const Mount& m) const
{
  const PixelOracle oracle(info_, m);
  Letterbox box = oracle.box(projector_->outputWindow()->width(), projector_->outputWindow()->height());
  box.left = box.top = 0;
  return oracle.toWindow(box, oracle.imagePixel(floor));
}

QImage ProjectorSceneTest::grabWithArrows(int at_least)
{
  return grabWhen([&](const QImage& image) { return countColour(image, kArrowMagenta) > at_least; });
}
}  // namespace rviz_projector_test
