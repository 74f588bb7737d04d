// The Stop zone properties of ProjectedPathDisplay (issue 25), as the Displays panel shows them: the
// group (off by default) and its children. Every change calls the display's updateStopZone() slot.
#pragma once

#include <QString>

#include "rviz_projector/core/speed_spacing.h"
#include "rviz_projector/core/stop_zone.h"

namespace rviz
{
class BoolProperty;
class ColorProperty;
class Config;
class Display;
class EnumProperty;
class FloatProperty;
class RosTopicProperty;
}  // namespace rviz

namespace rviz_projector
{
struct StopZoneProperties
{
  /// Creates the properties under `display` (a ProjectedPathDisplay: its slot is connected).
  explicit StopZoneProperties(rviz::Display* display);
  /// After loading `config`: the values that were unusable and replaced (empty when none). A config
  /// without the group (saved before it existed) loads with the stop zone off.
  QString checkLoaded(const rviz::Config& config) const;
  /// The drawing parameters the properties hold.
  StopZoneParameters parameters() const;
  /// The group is on and names a topic: what to subscribe to (empty: nothing).
  std::string wantedTopic() const;
  /// Speed-coded spacing (on only with the group on) for a robot driving at `speed` m/s.
  SpeedCoding speedCoding(double speed) const;

  rviz::BoolProperty* enabled;           ///< the group "Stop zone"
  rviz::RosTopicProperty* topic;         ///< child: nav_msgs/Odometry
  rviz::FloatProperty* deceleration;     ///< child, m/s^2
  rviz::FloatProperty* reaction_time;    ///< child, s
  rviz::EnumProperty* style;             ///< child: Filled / Hatched
  rviz::ColorProperty* color;            ///< child
  rviz::FloatProperty* alpha;            ///< child: opacity of the fill or stripes
  rviz::FloatProperty* width;            ///< child, metres across the path
  rviz::BoolProperty* speed_coded;       ///< child group "Speed-coded spacing" (off by default)
  rviz::FloatProperty* time_step;        ///< its child, s
  rviz::FloatProperty* min_spacing;      ///< its child, metres
};
}  // namespace rviz_projector
