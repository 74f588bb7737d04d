// The cue properties of ProjectedPathDisplay (issue 15), as the Displays panel shows them: names,
// defaults, ranges, help texts. Changes call the display's updateCues() slot; the State topic its
// updateStateTopic() slot.
#pragma once

#include <QString>

#include "rviz_projector/core/cue_drawing.h"
#include "rviz_projector/core/goal_cues.h"

namespace rviz
{
class BoolProperty;
class ColorProperty;
class Config;
class Display;
class FloatProperty;
class RosTopicProperty;
class StringProperty;
class TfFrameProperty;
}  // namespace rviz

namespace rviz_projector
{
struct PathCueProperties
{
  /// Creates the properties under `display` (a ProjectedPathDisplay: its slots are connected).
  explicit PathCueProperties(rviz::Display* display);
  /// After loading `config`: the values that were unusable and replaced (empty when none).
  QString checkLoaded(const rviz::Config& config) const;
  /// The cue settings the properties hold (angles in radians).
  /// Float properties' values as the decimals the user typed (speed 0.1 is 0.1, not 0.100000001:
  /// multiplied by an epoch time of 1.7e9 s that difference would move marching arrows by metres).
  PathCueSettings settings() const;
  GoalCueParameters goalParameters() const;

  rviz::TfFrameProperty* robot_frame;
  rviz::BoolProperty* horizon;
  rviz::FloatProperty* horizon_length;   ///< child of horizon
  rviz::FloatProperty* fade_length;      ///< child of horizon
  rviz::BoolProperty* marching;
  rviz::FloatProperty* marching_speed;   ///< child of marching
  rviz::RosTopicProperty* state_topic;
  rviz::ColorProperty* failed_color;     ///< child of state_topic
  rviz::ColorProperty* succeeded_color;  ///< child of state_topic
  rviz::BoolProperty* warning;           ///< child of state_topic
  rviz::FloatProperty* warning_time;     ///< child of warning
  rviz::FloatProperty* warning_hz;       ///< child of warning
  rviz::BoolProperty* turn_signal;
  rviz::FloatProperty* turn_angle;       ///< child of turn_signal, degrees
  rviz::FloatProperty* turn_distance;    ///< child of turn_signal
  rviz::FloatProperty* glyph_size;       ///< child of turn_signal
  rviz::FloatProperty* glyph_ahead;      ///< child of turn_signal
};
}  // namespace rviz_projector
