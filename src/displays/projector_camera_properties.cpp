#include "rviz_projector/displays/projector_camera_properties.h"

#include <algorithm>

#include <QGuiApplication>
#include <QScreen>
#include <ros/message_traits.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/string_property.h>
#include <nav_msgs/Odometry.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/displays/config_check.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output.h"

namespace rviz_projector
{
ProjectorCameraProperties::ProjectorCameraProperties(rviz::Display* display)
{
  topic = new rviz::RosTopicProperty(
      "Topic", ProjectorCameraDisplay::kDefaultTopic, QString::fromStdString(ros::message_traits::datatype<sensor_msgs::CameraInfo>()),
      "sensor_msgs/CameraInfo of the projector: resolution and lens (P, or K when P is all zero).", display,
      SLOT(resubscribe()), display);
  frame = new rviz::StringProperty(
      "Frame", "",
      "tf frame of the projector's optical frame (z forward, x right, y down). Empty: the CameraInfo "
      "header's frame_id.",
      display, SLOT(onFramePropertyChanged()), display);
  tf_timeout = new rviz::FloatProperty(
      "TF timeout", 1.0f,
      "Seconds: when the newest tf of the projector's pose in the fixed frame is older than this (its "
      "stamp against the ROS clock), the projector blanks (no scene, only the background) until fresh "
      "tf arrives. A chain of static transforms only never goes stale. 0: never.",
      display, SLOT(applyProjection()), display);
  tf_timeout->setMin(0.0f);
  screen = new rviz::EnumProperty(
      "Output screen", kAutomaticScreen,
      "Screen the projector is plugged into (its name, e.g. HDMI-1). Automatic: a screen of rviz's desktop other than "
      "rviz's own that no other projector uses.", display,
      SLOT(updateOutput()), display);
  QObject::connect(screen, SIGNAL(requestOptions(EnumProperty*)), display, SLOT(fillScreenOptions()));
  full_screen = new rviz::BoolProperty(
      "Full screen", true,
      "Full screen on the output screen (Esc in the window turns this off). Off: a normal window, e.g. for setting up on a "
      "laptop. With a single screen the window always opens windowed, never covering rviz.",
      display, SLOT(updateOutput()), display);
  background = new rviz::ColorProperty("Background color", QColor(0, 0, 0),
                                                 "Colour where nothing is drawn. Black projects no light.", display,
                                                 SLOT(applyProjection()), display);
  near_clip = new rviz::FloatProperty("Near clip", 0.05f, "Nearest distance drawn, metres.", display,
                                                SLOT(applyProjection()), display);
  near_clip->setMin(0.001f);
  near_clip->setMax(100.0f);
  far_clip = new rviz::FloatProperty("Far clip", 50.0f, "Farthest distance drawn, metres.", display,
                                               SLOT(applyProjection()), display);
  far_clip->setMin(0.01f);
  far_clip->setMax(10000.0f);
  max_lit_height = new rviz::FloatProperty(
      "Max lit height", 0.0f,
      "Metres above z = 0 of the fixed frame: nothing of rviz's scene above this height is drawn in the projector view "
      "(a clipping plane; the projector must be mounted above it). It clips only what is in the scene: a person the "
      "scanner does not see is not protected by it (see doc/guide/safety-mask.md). 0 = off.",
      display, SLOT(updateMaxLitHeight()), display);
  max_lit_height->setMin(0.0f);
  max_lit_height->setMax(100.0f);
  frame_rate = new rviz::IntProperty(
      "Frame rate limit", 60, "Most frames per second rendered into the output window; paced to the output screen's refresh when "
      "it is lower. Frames are rendered only when something shown changed.",
      display, SLOT(updateFrameRate()), display);
  frame_rate->setMin(1);
  frame_rate->setMax(240);
  anti_aliasing = new rviz::BoolProperty(
      "Anti-aliasing", false,
      "Smooth edges with 4x multisampling. Off by default: projected arrows are solid shapes, and on "
      "software or integrated graphics multisampling costs most of the frame time.",
      display, SLOT(updateOutput()), display);
  footprint = new rviz::BoolProperty(
      "Footprint in main view", true,
      "Draw the projector's frustum and the area it lights on the floor (z = 0) in rviz's main view.", display,
      SLOT(onFootprintPropertyChanged()), display);
  test_pattern = new rviz::EnumProperty(
      "Test pattern", kTestPatternOff,
      "Off: the scene. Metric grid: a grid on the floor (10 cm cells, bold lines every metre, a cross "
      "at the fixed frame's origin) to check the calibration with a tape measure. Crosshairs: numbered "
      "crosshairs at fixed projector pixels, white on black, independent of the mount, tf and the "
      "scene, to calibrate the mount (calibrate_projector --pattern lists the same pixels).",
      display, SLOT(updateTestPattern()), display);
  test_pattern->addOption(kTestPatternOff, static_cast<int>(TestPattern::Off));
  test_pattern->addOption(kTestPatternMetricGrid, static_cast<int>(TestPattern::MetricGrid));
  test_pattern->addOption(kTestPatternCrosshairs, static_cast<int>(TestPattern::Crosshairs));
  crosshair_rows = new rviz::IntProperty("Rows", CrosshairPatternSize::kDefaultRows,
                                         "Rows of crosshairs, spread over the central 80% of the image's height.",
                                         test_pattern, SLOT(updateTestPattern()), display);
  crosshair_cols = new rviz::IntProperty("Columns", CrosshairPatternSize::kDefaultCols,
                                         "Columns of crosshairs, spread over the central 80% of the image's width.",
                                         test_pattern, SLOT(updateTestPattern()), display);
  for (rviz::IntProperty* p : {crosshair_rows, crosshair_cols})
  {
    p->setMin(1);
    p->setMax(CrosshairPatternSize::kMaxRowsCols);
  }
  showTestPatternOptions();
  image_output = new rviz::BoolProperty(
      "Image output", false,
      "Also publish the rendered view as sensor_msgs/Image (+ CameraInfo) for remote monitoring or recording.",
      display, SLOT(updateImageOutput()), display);
  image_topic = new rviz::StringProperty("Image topic", "/projector/rendered/image",
                                                   "Topic of the published image; CameraInfo goes to the "
                                                   "sibling topic camera_info.",
                                                   image_output, SLOT(updateImageOutput()), display);
  image_rate = new rviz::FloatProperty("Image rate", 10.0f, "Images published per second.",
                                                 image_output, SLOT(updateImageOutput()), display);
  image_rate->setMin(0.1f);
  image_rate->setMax(120.0f);
  pattern_topic = new rviz::RosTopicProperty(
      "Pattern topic", "/projector/pattern", QString::fromStdString(ros::message_traits::datatype<sensor_msgs::Image>()),
      "sensor_msgs/Image shown 1:1 full screen instead of the scene while it arrives (calibrate_projector --camera "
      "shows its structured-light patterns this way): exactly the projector's width x height, mono8/rgb8/bgr8/rgba8/"
      "bgra8; a 0 x 0 image ends it. The header of each pattern is echoed on <topic>/shown (std_msgs/Header) once the "
      "frame showing it went to the screen. Empty: off.",
      display, SLOT(updatePatternTopic()), display);
  pattern_timeout = new rviz::FloatProperty(
      "Timeout", 10.0f,
      "Seconds without a new pattern after which the scene comes back (a crashed sender never leaves the projector "
      "on a pattern). 0: never.",
      pattern_topic, nullptr, display);
  pattern_timeout->setMin(0.0f);
  pattern_timeout->setMax(3600.0f);
  createMotionProperties(display);
}

void ProjectorCameraProperties::createMotionProperties(rviz::Display* display)
{
  motion = new rviz::Property(
      "Motion compensation", QVariant(),
      "Keeps world-locked content (arrows) still on the floor while the robot moves: each frame is drawn from the "
      "projector pose predicted for the moment its light is on the floor (now + measured render delay + half a frame + "
      "Projector input lag), from the projector's recent tf poses or the Odometry topic's twist.",
      display);
  motion_enabled = new rviz::BoolProperty(
      "Enabled", true,
      "Predict the projector's pose. Off: every frame is drawn from the newest tf, which is already old when the light "
      "leaves the lens.",
      motion);
  motion_input_lag = new rviz::FloatProperty(
      "Projector input lag", 0.0f,
      "Milliseconds from a frame reaching the projector's input to its light on the floor (the projector's input lag, "
      "from its data sheet or a review, or measured: see doc/guide/motion-compensation.md). 0 = none.",
      motion);
  motion_input_lag->setMin(0.0f);
  motion_input_lag->setMax(500.0f);
  motion_odometry = new rviz::RosTopicProperty(
      "Odometry topic", "", QString::fromStdString(ros::message_traits::datatype<nav_msgs::Odometry>()),
      "nav_msgs/Odometry of the robot's base (its twist, in child_frame_id): the motion to predict with, more current "
      "than differences of tf poses. Empty: the projector's own tf poses.",
      motion, SLOT(updateMotionOdometry()), display);
  motion_max = new rviz::FloatProperty(
      "Max prediction", 150.0f,
      "Milliseconds: the longest extrapolation beyond the newest pose. A longer wanted prediction is cut here.", motion);
  motion_max->setMin(0.0f);
  motion_max->setMax(1000.0f);
  motion_state = new rviz::StringProperty("Prediction", "", "What the prediction does now (read only).", motion);
  motion_state->setReadOnly(true);
}

double ProjectorCameraProperties::inputLag() const
{
  return std::max(0.0f, motion_input_lag->getFloat()) * 1e-3;
}

double ProjectorCameraProperties::maxPrediction() const
{
  return std::max(0.0f, motion_max->getFloat()) * 1e-3;
}

TestPattern ProjectorCameraProperties::testPattern() const
{
  // The options carry the enum's values (addOption above); an unknown text gives 0, Off.
  return static_cast<TestPattern>(test_pattern->getOptionInt());
}

void ProjectorCameraProperties::showTestPatternOptions()
{
  const bool crosshairs = testPattern() == TestPattern::Crosshairs;
  crosshair_rows->setHidden(!crosshairs);
  crosshair_cols->setHidden(!crosshairs);
}

QString ProjectorCameraProperties::checkLoaded(const rviz::Config& config) const
{
  ConfigCheck check;
  // Test pattern was a BoolProperty until issue 12: `true` is today's Metric grid, `false` Off.
  rviz::Config pattern = config.mapGetChild(test_pattern->getName());
  if (pattern.getType() == rviz::Config::Map)
  {
    pattern = pattern.mapGetChild("Value");
  }
  const QString legacy = test_pattern->getValue().toString().trimmed().toLower();
  if (legacy == "true" || legacy == "false")
  {
    test_pattern->setString(legacy == "true" ? kTestPatternMetricGrid : kTestPatternOff);
  }
  else
  {
    check.choice(pattern, test_pattern, {kTestPatternOff, kTestPatternMetricGrid, kTestPatternCrosshairs},
                 kTestPatternOff);
  }
  check.number(config.mapGetChild(test_pattern->getName()).mapGetChild(crosshair_rows->getName()), crosshair_rows);
  check.number(config.mapGetChild(test_pattern->getName()).mapGetChild(crosshair_cols->getName()), crosshair_cols);
  for (rviz::Property* p : {static_cast<rviz::Property*>(tf_timeout), static_cast<rviz::Property*>(near_clip),
                            static_cast<rviz::Property*>(far_clip), static_cast<rviz::Property*>(frame_rate),
                            static_cast<rviz::Property*>(max_lit_height)})
  {
    check.number(config.mapGetChild(p->getName()), p);
  }
  check.number(config.mapGetChild(image_output->getName()).mapGetChild(image_rate->getName()), image_rate);
  check.number(config.mapGetChild(pattern_topic->getName()).mapGetChild(pattern_timeout->getName()), pattern_timeout);
  check.number(config.mapGetChild(motion->getName()).mapGetChild(motion_input_lag->getName()), motion_input_lag);
  check.number(config.mapGetChild(motion->getName()).mapGetChild(motion_max->getName()), motion_max);
  return check.report();
}

void ProjectorCameraProperties::fillScreenOptions()
{
  screen->clearOptions();
  screen->addOption(kAutomaticScreen);
  for (QScreen* s : QGuiApplication::screens())
  {
    screen->addOption(s->name());
  }
}

std::string ProjectorCameraProperties::normaliseScreen()
{
  const std::string name = ProjectorOutput::screenName(screen->getString());
  screen->setString(QString::fromStdString(name));
  return name;
}

OutputRequest ProjectorCameraProperties::outputRequest(std::uint32_t image_width, std::uint32_t image_height,
                                                       QScreen* rviz_screen) const
{
  OutputRequest request;
  request.screen = ProjectorOutput::screenName(screen->getString());
  request.full_screen = full_screen->getBool();
  request.fsaa = anti_aliasing->getBool() ? 4 : 0;
  request.image_width = image_width;
  request.image_height = image_height;
  // The primary screen while rviz's window has none yet (start-up) or rviz is embedded without one.
  request.rviz_screen = rviz_screen ? rviz_screen : QGuiApplication::primaryScreen();
  return request;
}
}  // namespace rviz_projector
