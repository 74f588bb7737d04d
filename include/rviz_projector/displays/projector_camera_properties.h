// The properties of ProjectorCameraDisplay, as the Displays panel shows them (names, defaults,
// ranges, help texts). Changes call the display's slots.
#pragma once

#include <QString>

namespace rviz
{
class BoolProperty;
class ColorProperty;
class Config;
class Display;
class EnumProperty;
class FloatProperty;
class IntProperty;
class RosTopicProperty;
class StringProperty;
}  // namespace rviz

namespace rviz_projector
{
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

  rviz::RosTopicProperty* topic;
  rviz::StringProperty* frame;
  rviz::FloatProperty* tf_timeout;  ///< seconds, 0 = never
  rviz::EnumProperty* screen;
  rviz::BoolProperty* full_screen;
  rviz::ColorProperty* background;
  rviz::FloatProperty* near_clip;
  rviz::FloatProperty* far_clip;
  rviz::IntProperty* frame_rate;
  rviz::BoolProperty* anti_aliasing;
  rviz::BoolProperty* footprint;
  rviz::EnumProperty* test_pattern;
  rviz::IntProperty* crosshair_rows;     ///< child of test_pattern, Crosshairs only
  rviz::IntProperty* crosshair_cols;     ///< child of test_pattern, Crosshairs only
  rviz::BoolProperty* image_output;
  rviz::StringProperty* image_topic;
  rviz::FloatProperty* image_rate;
};
}  // namespace rviz_projector
