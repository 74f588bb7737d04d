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
struct ProjectorCameraProperties
{
  /// Creates the properties under `display` (a ProjectorCameraDisplay: its slots are connected).
  explicit ProjectorCameraProperties(rviz::Display* display);
  /// After loading `config`: the values that were unusable and replaced (empty when none).
  QString checkLoaded(const rviz::Config& config) const;

  rviz::RosTopicProperty* topic;
  rviz::StringProperty* frame;
  rviz::EnumProperty* screen;
  rviz::BoolProperty* full_screen;
  rviz::ColorProperty* background;
  rviz::FloatProperty* near_clip;
  rviz::FloatProperty* far_clip;
  rviz::IntProperty* frame_rate;
  rviz::BoolProperty* anti_aliasing;
  rviz::BoolProperty* footprint;
  rviz::BoolProperty* test_pattern;
  rviz::BoolProperty* image_output;
  rviz::StringProperty* image_topic;
  rviz::FloatProperty* image_rate;
};
}  // namespace rviz_projector
