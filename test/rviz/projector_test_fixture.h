// Shared by the ProjectorCamera rviz tests: a fixture with a ProjectorCamera fed CameraInfo and tf,
// floor targets (ProjectedPath destination discs), reading the output window back from the X
// server, and the independent pixel oracle the pixels are judged by.
//
// The oracle never asks the code under test (PinholeModel, the display): a floor point's image
// pixel comes from image_geometry::PinholeCameraModel on the raw CameraInfo (P with Tx/Ty,
// binning, ROI; ROS pixel centres at integer coordinates), the image size from the CameraInfo's
// fields, and the letterbox rectangle from the window size by the rule written out in letterbox().
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <QImage>
#include <image_geometry/pinhole_camera_model.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <tf2/LinearMath/Transform.h>

#include "rviz_projector/core/vec2.h"
#include "rviz_projector/core/vec3.h"
#include "optical_orientation.h"
#include "rviz_test_fixture.h"

namespace rviz_projector
{
class ProjectedPathDisplay;
class ProjectorCameraDisplay;
}  // namespace rviz_projector

namespace rviz_projector_test
{
using rviz_projector::Vec2;
using rviz_projector::Vec3;

constexpr const char* kInfoTopic = "/test/projector/camera_info";
constexpr const char* kOpticalFrame = "test_projector_optical";
const QRgb kBlack = qRgb(0, 0, 0);
const QRgb kArrowMagenta = qRgb(255, 0, 255);

/// Pose of the projector's optical frame in map.
struct Mount
{
  Vec3 position;
  double qx, qy, qz, qw;
};

/// Optical frame of a projector body at `position` (x forward, z up) with roll/pitch/yaw.
Mount bodyMount(const Vec3& position, double roll, double pitch, double yaw);
/// A demo-like set-up: 1280x800 projector 1.2 m up, pitched down 0.9 rad, looking along +x.
extern const Mount kDemoMount;

/// An ideal lens in the optical frame kOpticalFrame (K = P, no distortion).
sensor_msgs::CameraInfo projectorInfo(unsigned w, unsigned h, double f, double cx, double cy);
/// The issue 24 projector: 1280x800, f = 1900, centred, with plumb_bob distortion `d`.
sensor_msgs::CameraInfo distortedInfo(const std::vector<double>& d);

/// Integer window rectangle the image is drawn into.
struct Letterbox
{
  int left = 0, top = 0, width = 0, height = 0;
};

/// The letterbox rule, by hand: an image that fits exactly along one axis and is not larger along
/// the other is shown 1:1; otherwise it is scaled by min(ww/iw, wh/ih), its size rounded (at least
/// 1), and centred with integer division.
Letterbox letterbox(int window_width, int window_height, int image_width, int image_height);

/// Where a projector at `mount` with the lens of `info` must show floor points.
class PixelOracle
{
public:
  PixelOracle(const sensor_msgs::CameraInfo& info, const Mount& mount);

  /// Size of the image the CameraInfo describes: the ROI (or the whole sensor) over the binning.
  int imageWidth() const { return width_; }
  int imageHeight() const { return height_; }
  /// image_geometry's fx of that image (binned).
  double fx() const { return model_.fx(); }
  /// Image pixel (pixel centres at integer coordinates) of a floor point: project3dToPixel.
  Vec2 imagePixel(const Vec2& floor) const;
  /// Floor point on the ray of an image pixel (projectPixelTo3dRay meets z = 0).
  Vec2 floorPoint(const Vec2& pixel) const;
  /// Depth (optical z) of a floor point.
  double depth(const Vec2& floor) const;
  /// Image pixel of the area centroid of a floor disc's outline as the lens shows it (a disc seen
  /// at an angle is not centred on its centre's projection); `area` gets its area in image pixels.
  Vec2 discCentroid(const Vec2& centre, double diameter, double* area = nullptr) const;
  /// Image pixel -> window pixel (pixel-centre coordinates) through the letterbox.
  Vec2 toWindow(const Letterbox& box, const Vec2& image_pixel) const;
  /// The letterbox of this image in a window of the given size.
  Letterbox box(int window_width, int window_height) const
  {
    return letterbox(window_width, window_height, width_, height_);
  }

private:
  cv::Point3d optical(const Vec2& floor) const;

  image_geometry::PinholeCameraModel model_;
  // A non-zero D (issue 24): the raw pixels are cv::projectPoints with K (ROI and binning applied
  // by hand) and D, the projector's pixels through its lens.
  bool distorted_ = false;
  cv::Matx33d raw_k_;
  std::vector<double> d_;
  tf2::Transform pose_;  // optical frame in map
  int width_ = 0, height_ = 0;
};

/// Centroid (pixel-centre coordinates) of the green pixels within `radius` of `around`.
bool greenCentroid(const QImage& image, const Vec2& around, int radius, Vec2& centroid, int& count);
/// Saves `image` as RP_TEST_SHOTS/<name>.png when that folder is set (pictures for the guide).
void saveShot(const QImage& image, const char* name);
/// Floor points along y = 0 from x `from` every 5 cm, the last exactly at `to`.
std::vector<Vec2> lineAlongX(double from, double to);
/// First and last columns and rows holding a pixel brighter than mid-grey in all channels
/// (-1 when none); returned as a rectangle left, top, width, height.
Letterbox litBounds(const QImage& image);

class ProjectorCameraTest : public RvizTest
{
protected:
  void SetUp() override;

  void mount(const Mount& m);
  /// A ProjectedPath with a single pose: just its destination disc, a target on the floor.
  void addTarget(const Vec2& p, double diameter);
  /// Moves target `index` (in the order added) to floor point `p`.
  void moveTarget(std::size_t index, const Vec2& p);
  bool targetsReady() const;
  /// Renders a frame and reads the output window's pixels back from the X server: exactly what the
  /// projector shows. (OGRE's own read-back of the back buffer is off by a fraction of a pixel on
  /// Mesa's software GL, so it is not used to judge accuracy.)
  QImage grab();
  /// Grabs until two grabs in a row are the same (the X server has the frame) and `ok` holds for
  /// it, or `timeout` passes; returns the last grab either way.
  QImage grabWhen(const std::function<bool(const QImage&)>& ok, double timeout = 5.0);
  /// Waits until the display rendered `frames` more frames.
  bool waitForFrames(int frames, double timeout = 5.0);
  /// The window size as shown in `window_image`, letterboxed for `oracle`'s image.
  static QImage imagePart(const QImage& window_image, const PixelOracle& oracle);

  /// The pixel-accuracy check for one projector set-up: targets are floor discs about
  /// kTargetPixels across in the image, centred on the floor points seen at image `pixels`.
  /// Returns the largest error, the larger of window pixels and image pixels.
  double pixelAccuracy(const sensor_msgs::CameraInfo& info, const Mount& m, const std::vector<Vec2>& pixels);

  ros::Publisher info_pub_;
  rviz_projector::ProjectorCameraDisplay* projector_ = nullptr;
  std::vector<ros::Publisher> target_pubs_;
  std::vector<rviz_projector::ProjectedPathDisplay*> targets_;
  int grabs_ = 0;
};

/// A 1280x800 projector at kDemoMount with its lens, ready to show paths.
class ProjectorSceneTest : public ProjectorCameraTest
{
protected:
  void SetUp() override;
  rviz_projector::ProjectedPathDisplay* addPath(const std::string& topic, const std::vector<Vec2>& points);
  /// The robot (base_link) standing at (`robot_x`, 0) facing `yaw` in map, and a ProjectedPath of
  /// `points` on /test/plan drawn on the floor itself (Height above floor 0: the oracle's points
  /// lie on the floor). Null if the display could not be made.
  rviz_projector::ProjectedPathDisplay* addFloorPathFromRobot(const std::vector<Vec2>& points, double robot_x,
                                                              double yaw = 0.0);
  /// The image part (letterbox removed) of a grabbed window, for info_.
  QImage imagePart(const QImage& window) const;
  /// Where the oracle puts a floor point in the image part of the window (letterbox removed):
  /// image_geometry's pixel, scaled by the letterbox of the current window size.
  Vec2 windowPixel(const Vec2& floor, const Mount& m = kDemoMount) const;
  /// The grabbed window once the path's arrows are in it (more than `at_least` pixels).
  QImage grabWithArrows(int at_least = 100);

  sensor_msgs::CameraInfo info_ = projectorInfo(1280, 800, 1300, 639.5, 399.5);
  ros::Publisher path_pub_;
};
}  // namespace rviz_projector_test
