// Fixtures of the bad-input matrix (robustness_*_test.cpp, one executable test_robustness): the
// shared constants, RobustnessTest, PathRobustness and CameraRobustness (LifecycleRobustness
// builds on it).
#pragma once

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <QApplication>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/visualization_manager.h>
#include <rviz/yaml_config_reader.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "robustness_helpers.h"
#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/arrow_solid.h"
#include "rviz_projector/core/path_triangles.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_test_fixture.h"

using rviz_projector::ProjectedPathDisplay;
using rviz_projector::ProjectorCameraDisplay;
using rviz_projector::Vec3;
using rviz_projector_test::countColour;
using rviz_projector_test::grabProjector;
using rviz_projector_test::line;
using rviz_projector_test::makePath;
using rviz_projector_test::projectorWindows;
using rviz_projector_test::Status;

namespace rviz_projector_robustness
{
inline const double kNan = std::numeric_limits<double>::quiet_NaN();
inline const double kInf = std::numeric_limits<double>::infinity();
inline const QRgb kMagenta = qRgb(255, 0, 255);
inline const QRgb kBlack = qRgb(0, 0, 0);
inline constexpr const char* kPathTopic = "/robustness/plan";
inline constexpr const char* kInfoTopic = "/robustness/camera_info";
inline constexpr const char* kOptical = "robustness_projector_optical";

inline std::string text(const Status& s) { return s.text.toStdString(); }

}  // namespace rviz_projector_robustness

using namespace rviz_projector_robustness;  // NOLINT: test fixtures share these names

class RobustnessTest : public rviz_projector_test::RvizTest
{
protected:
  /// Messages that went through a MessageFilterDisplay's tf filter ("N messages received").
  static int messagesReceived(rviz::Display* display)
  {
    const Status s = statusOf(display, "Topic");
    return s.text.endsWith(" messages received") ? s.text.split(' ').front().toInt() : 0;
  }
};

// ---- Path -------------------------------------------------------------------------------------

class PathRobustness : public RobustnessTest
{
protected:
  void SetUp() override
  {
    RvizTest::SetUp();
    publishStaticTransform("map", "odom", 1.0, 0.5, 0.0, 0.0);
    publisher_ = nh_.advertise<nav_msgs::Path>(kPathTopic, 1, true);
    display_ = dynamic_cast<ProjectedPathDisplay*>(rviz_->addDisplay("rviz_projector/ProjectedPath", "Path"));
    ASSERT_NE(display_, nullptr);
    display_->subProp("Topic")->setValue(kPathTopic);
  }

  /// Publishes and waits until the display has processed it.
  bool publishAndWait(const nav_msgs::Path& path, double timeout = 10.0)
  {
    const int before = messagesReceived(display_);
    publisher_.publish(boost::make_shared<nav_msgs::Path>(path));  // shared_ptr: no copy in-process
    return waitFor([&] { return messagesReceived(display_) > before; }, timeout);
  }

  /// The main view still renders, and the path display is in it.
  void expectRvizRenders()
  {
    const QImage image = rviz_->renderMainView();
    EXPECT_FALSE(image.isNull()) << "rviz keeps rendering";
  }

  Status path() { return statusOf(display_, "Path"); }

  ros::Publisher publisher_;
  ProjectedPathDisplay* display_ = nullptr;
};

// ---- CameraInfo -------------------------------------------------------------------------------

class CameraRobustness : public RobustnessTest
{
protected:
  void SetUp() override
  {
    RvizTest::SetUp();
    static_tf_->sendTransform(rviz_projector_test::projectorMount("map", kOptical, 0.0, 0.0, 1.2, 0.9));
    info_pub_ = nh_.advertise<sensor_msgs::CameraInfo>(kInfoTopic, 1, true);
    path_pub_ = nh_.advertise<nav_msgs::Path>(kPathTopic, 1, true);
    // Arrows in front of the projector, to see whether it projects anything.
    rviz::Display* path = rviz_->addDisplay("rviz_projector/ProjectedPath", "Path");
    path->subProp("Topic")->setValue(kPathTopic);
    path_pub_.publish(makePath("map", line(Vec3{0.5, 0, 0}, Vec3{2.2, 0, 0}, 40)));
    projector_ = dynamic_cast<ProjectorCameraDisplay*>(rviz_->addDisplay("rviz_projector/ProjectorCamera", "Projector"));
    ASSERT_NE(projector_, nullptr);
    projector_->subProp("Topic")->setValue(kInfoTopic);
    ASSERT_TRUE(showGood());
  }

  bool showGood()
  {
    info_pub_.publish(good_);
    return waitFor([&] { return projector_->hasLens() && projector_->outputWindow() && projector_->outputWindow()->isVisible(); }) &&
           waitFor([&] { return countColour(grabProjector(projector_), kMagenta) > 100; });
  }

  /// Publishes a CameraInfo and waits until the display has taken it (its status changed).
  Status publishInfo(const sensor_msgs::CameraInfo& info)
  {
    // Clear the slate with the good one, then the bad one: the status text must change.
    info_pub_.publish(good_);
    waitFor([&] { return projector_->hasLens() && text(statusOf(projector_, "CameraInfo")) == good_text_; });
    info_pub_.publish(info);
    waitFor([&] { return text(statusOf(projector_, "CameraInfo")) != good_text_; }, 3.0);
    return statusOf(projector_, "CameraInfo");
  }

  void expectBackgroundOnly(const std::string& what)
  {
    const QImage frame = grabProjector(projector_);
    ASSERT_FALSE(frame.isNull()) << what;
    EXPECT_EQ(countColour(frame, kBlack), frame.width() * frame.height()) << what << ": background only";
    EXPECT_FALSE(rviz_->renderMainView().isNull()) << what << ": rviz keeps rendering";
  }

  void expectProjects(const std::string& what)
  {
    EXPECT_TRUE(waitFor([&] { return countColour(grabProjector(projector_), kMagenta) > 100; }, 3.0))
        << what << ": the arrows are projected";
    EXPECT_FALSE(rviz_->renderMainView().isNull()) << what << ": rviz keeps rendering";
  }

  sensor_msgs::CameraInfo good_ = rviz_projector_test::cameraInfo(kOptical, 1280, 800, 1300, 639.5, 399.5);
  const std::string good_text_ = "1280x800, fx 1300, fy 1300, cx 639.5, cy 399.5";
  ros::Publisher info_pub_, path_pub_;
  ProjectorCameraDisplay* projector_ = nullptr;
};
