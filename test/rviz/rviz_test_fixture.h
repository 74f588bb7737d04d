// A real rviz (VisualizationManager + RenderPanel in a QApplication, under an X server) for tests
// that go through the same path as a user: pluginlib class names, properties, topics, pixels.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <QImage>
#include <QString>
#include <QVariant>
#include <ros/ros.h>
#include <rviz/properties/status_property.h>
#include <sensor_msgs/CameraInfo.h>
#include <geometry_msgs/TransformStamped.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "optical_orientation.h"

namespace rviz
{
class Display;
class RenderPanel;
class VisualizationManager;
}  // namespace rviz

namespace rviz_projector_test
{
/// One status line of a display as the user sees it in the Displays panel.
struct Status
{
  bool present = false;
  rviz::StatusProperty::Level level = rviz::StatusProperty::Ok;
  QString text;
};

/// An rviz instance: created per test (or one after the other in a test, for config round trips;
/// rviz cannot hold two VisualizationManagers at once).
class RvizInstance
{
public:
  RvizInstance(int width, int height);
  ~RvizInstance();

  rviz::VisualizationManager* manager() const { return manager_; }
  rviz::RenderPanel* panel() const { return panel_; }
  /// Adds a display by its pluginlib class name, as the "Add display" dialog does.
  rviz::Display* addDisplay(const QString& class_id, const QString& name);
  /// Main view looking straight down (rviz/TopDownOrtho), centred on (x, y) of the fixed frame.
  void setTopDownView(double x, double y, double pixels_per_metre);
  /// Renders the main view now and returns its pixels.
  QImage renderMainView();
  /// Pixel of a fixed-frame floor point in the top-down main view.
  QPoint topDownPixel(double x, double y) const;

private:
  rviz::RenderPanel* panel_;
  rviz::VisualizationManager* manager_;
  double view_x_ = 0.0, view_y_ = 0.0, scale_ = 100.0;
};

class RvizTest : public ::testing::Test
{
protected:
  void SetUp() override;
  void TearDown() override;

  /// Processes Qt events and ROS callbacks (rviz's update loop runs inside) for `seconds`.
  static void spinFor(double seconds);
  /// Spins until `done` holds or `timeout` seconds pass; returns `done()`.
  static bool waitFor(const std::function<bool()>& done, double timeout = 5.0);
  /// Spins until rviz has run its update (displays' update(), view controller, main view render)
  /// `frames` more times, or `timeout` seconds pass; returns whether it did.
  bool waitForMainViewFrames(int frames, double timeout = 5.0);
  static Status statusOf(rviz::Display* display, const QString& name);
  /// Publishes a static transform parent -> child (x, y, z, yaw).
  void publishStaticTransform(const std::string& parent, const std::string& child, double x, double y, double z,
                              double yaw);
  /// A display of `class_id` (a ProjectedPath unless told) with `values` set in its group `group`,
  /// the group switched on, saved to a file and loaded into a fresh rviz (this one closed): expects
  /// the switch and every value as the first rviz showed it. Returns those shown values (the text
  /// of each property). A name may be a path of child names joined by '/' (a group inside the group).
  std::map<std::string, std::string> expectGroupSavedAndLoaded(
      const QString& group, const std::map<std::string, QVariant>& values,
      const QString& class_id = "rviz_projector/ProjectedPath");

  ros::NodeHandle nh_;
  std::unique_ptr<RvizInstance> rviz_;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> static_tf_;
};

/// Whether two colours match within `tolerance` per channel (0..255).
bool sameColour(QRgb a, QRgb b, int tolerance = 8);
/// Pixels of `image` matching `colour` within `tolerance` per channel.
int countColour(const QImage& image, QRgb colour, int tolerance = 30);
/// CameraInfo of an ideal, centred-or-not pinhole lens (K and P consistent, no distortion).
sensor_msgs::CameraInfo cameraInfo(const std::string& frame, unsigned w, unsigned h, double f, double cx, double cy);
/// "r,g,b" for test messages.
std::string describe(QRgb c);
/// A transform parent -> child stamped now: translation and rotation.
geometry_msgs::TransformStamped stampedTransform(const std::string& parent, const std::string& child, double x,
                                                double y, double z, const Quaternion& rotation);
/// Start time for a test that sets ROS time itself (ros::Time::setNow): a multiple of `multiple`
/// seconds of wall time, at least 2 s after the previous test's start in this process. Test time
/// never goes back from one test to the next: rviz resets every display when ROS time jumps back,
/// at its next update, which could come after the test's first message and clear it (seen in CI
/// under load).
ros::Time monotonicTestStart(double multiple = 1.0);
}  // namespace rviz_projector_test
