// The properties of ProjectorCameraDisplay, as the Displays panel shows them (names, defaults,
// ranges, help texts). Changes call the display's slots.
#pragma once

#include <cstdint>
#include <string>

#include <QString>

class QScreen;

namespace rviz
{
class BoolProperty;
class ColorProperty;
class Config;
class Display;
class EnumProperty;
class FloatProperty;
class IntProperty;
class Property;
class RosTopicProperty;
class StringProperty;
}  // namespace rviz

namespace rviz_projector
{
struct OutputRequest;

/// The Test pattern property's choices (names as the Displays panel shows them).
enum class TestPattern
{
  Off = 0,
  MetricGrid = 1,
  Crosshairs = 2
};
constexpr const char* kTestPatternOff = "Off";
constexpr const char* kTestPatternMetricGrid = "Metric grid";
constexpr const char* kTestPatternCrosshairs = "Crosshairs";

struct ProjectorCameraProperties
{
  /// Creates the properties under `display` (a ProjectorCameraDisplay: its slots are connected).
  explicit ProjectorCameraProperties(rviz::Display* display);
  /// After loading `config`: the values that were unusable and replaced (empty when none).
  /// Also turns the Test pattern of configs saved before issue 12 (`true`/`false`) into a choice.
  QString checkLoaded(const rviz::Config& config) const;
  TestPattern testPattern() const;
  /// Shows Rows and Columns only for Crosshairs.
  void showTestPatternOptions();
  /// The Output screen's choices: Automatic, then every connected screen by name.
  void fillScreenOptions();
  /// The screen name in Output screen; labels of older configs ("NAME (WxH at X,Y)") become the
  /// plain name, in the property too.
  std::string normaliseScreen();
  /// The output window these properties ask for, for an image of this size (0 x 0: no lens yet),
  /// rviz's main window being on `rviz_screen`.
  OutputRequest outputRequest(std::uint32_t image_width, std::uint32_t image_height, QScreen* rviz_screen) const;
  /// Motion compensation's settings, seconds.
  double inputLag() const;
  double maxPrediction() const;
  /// Creates the Motion compensation group (issue 14).
  void createMotionProperties(rviz::Display* display);

  rviz::RosTopicProperty* topic;
  rviz::StringProperty* frame;
  rviz::FloatProperty* tf_timeout;  ///< seconds, 0 = never
  rviz::EnumProperty* screen;
  rviz::BoolProperty* full_screen;
  rviz::ColorProperty* background;
  rviz::FloatProperty* near_clip;
  rviz::FloatProperty* far_clip;
  rviz::FloatProperty* max_lit_height;  ///< metres, 0 = off
  rviz::IntProperty* frame_rate;
  rviz::BoolProperty* anti_aliasing;
  rviz::BoolProperty* footprint;
  rviz::EnumProperty* test_pattern;
  rviz::IntProperty* crosshair_rows;     ///< child of test_pattern, Crosshairs only
  rviz::IntProperty* crosshair_cols;     ///< child of test_pattern, Crosshairs only
  rviz::BoolProperty* image_output;
  rviz::StringProperty* image_topic;
  rviz::FloatProperty* image_rate;
  rviz::RosTopicProperty* pattern_topic;  ///< sensor_msgs/Image shown 1:1 (ProjectorPattern); empty = off
  rviz::FloatProperty* pattern_timeout;   ///< child of pattern_topic; seconds, 0 = never
  // Motion compensation (issue 14): a group; its values are read frame by frame.
  rviz::Property* motion;
  rviz::BoolProperty* motion_enabled;
  rviz::FloatProperty* motion_input_lag;    ///< ms
  rviz::RosTopicProperty* motion_odometry;  ///< nav_msgs/Odometry, empty = tf
  rviz::FloatProperty* motion_max;          ///< ms
  rviz::StringProperty* motion_state;       ///< read only: what the prediction does
};
}  // namespace rviz_projector
