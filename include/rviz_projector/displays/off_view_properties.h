// The Off-view cue properties of ProjectedPathDisplay (issue 25 part 3), as the Displays panel shows
// them: the group (off by default) and its children. Every change calls the display's
// updateOffView() slot.
#pragma once

#include <string>

#include <QString>

#include "rviz_projector/core/off_view_cue.h"

namespace rviz
{
class BoolProperty;
class ColorProperty;
class Config;
class Display;
class FloatProperty;
class RosTopicProperty;
}  // namespace rviz

namespace rviz_projector
{
struct OffViewProperties
{
  /// Creates the properties under `display` (a ProjectedPathDisplay: its slot is connected).
  explicit OffViewProperties(rviz::Display* display);
  /// After loading `config`: the values that were unusable and replaced (empty when none). A config
  /// without the group (saved before it existed) loads with the cue off.
  QString checkLoaded(const rviz::Config& config) const;
  /// The cue's parameters the properties hold (the others at OffViewParameters' defaults).
  OffViewParameters parameters() const;
  /// The group is on and names a topic: what to subscribe to (empty: nothing).
  std::string wantedTopic() const;

  rviz::BoolProperty* enabled;          ///< the group "Off-view cue"
  rviz::RosTopicProperty* topic;        ///< child "Projector info topic": sensor_msgs/CameraInfo
  rviz::FloatProperty* look_ahead;      ///< child, metres of path judged
  rviz::FloatProperty* final_approach;  ///< child, metres of path left
  rviz::FloatProperty* size;            ///< child "Arrow size": arrow length and glyph size, metres
  rviz::ColorProperty* color;           ///< child
  rviz::FloatProperty* alpha;           ///< child: opacity (times the display's Alpha)
};
}  // namespace rviz_projector
