// The Corridor properties of ProjectedPathDisplay (issue 25), as the Displays panel shows them: the
// group (off by default) and its children. Every change calls the display's updateCorridor() slot.
#pragma once

#include <string>

#include <QString>

#include "rviz_projector/core/swept_corridor.h"

namespace rviz
{
class BoolProperty;
class ColorProperty;
class Config;
class Display;
class EnumProperty;
class FloatProperty;
class RosTopicProperty;
class StringProperty;
}  // namespace rviz

namespace rviz_projector
{
struct CorridorProperties
{
  enum class Source
  {
    Radius,
    Polygon,
    Topic,
  };

  /// Creates the properties under `display` (a ProjectedPathDisplay: its slot is connected).
  explicit CorridorProperties(rviz::Display* display);
  /// After loading `config`: the values that were unusable and replaced (empty when none). A config
  /// without the group (saved before it existed) loads with the corridor off.
  QString checkLoaded(const rviz::Config& config) const;
  /// The sweep's parameters the properties hold.
  CorridorParameters parameters() const;
  Source source() const;
  /// Band (filled) rather than the two edges.
  bool band() const;
  /// The group is on with the footprint from a topic: what to subscribe to (empty: nothing).
  std::string wantedTopic() const;

  rviz::BoolProperty* enabled;         ///< the group "Corridor"
  rviz::EnumProperty* footprint;       ///< child: Radius / Polygon / Topic
  rviz::FloatProperty* radius;         ///< child, metres
  rviz::StringProperty* polygon;       ///< child: "[[x, y], ...]" in the robot frame
  rviz::RosTopicProperty* topic;       ///< child: geometry_msgs/PolygonStamped
  rviz::FloatProperty* length;         ///< child, metres of path ahead of the robot
  rviz::EnumProperty* style;           ///< child: Edges / Band
  rviz::FloatProperty* edge_width;     ///< child, metres
  rviz::ColorProperty* color;          ///< child
  rviz::FloatProperty* alpha;          ///< child: the band's opacity
};
}  // namespace rviz_projector
