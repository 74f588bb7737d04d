// The Acknowledge properties of ProjectionMaskDisplay (issue 25, part 4: "I have seen you"), as the
// Displays panel shows them: the group (off by default) and its children. Every change calls the
// display's updateAcknowledge() slot.
#pragma once

#include <string>

#include <QString>

#include "rviz_projector/core/acknowledge_arc.h"
#include "rviz_projector/core/person_clusters.h"
#include "rviz_projector/core/person_tracker.h"

namespace rviz
{
class BoolProperty;
class ColorProperty;
class Config;
class Display;
class FloatProperty;
class IntProperty;
class RosTopicProperty;
class TfFrameProperty;
}  // namespace rviz

namespace rviz_projector
{
struct AcknowledgeProperties
{
  /// Creates the properties under `display` (a ProjectionMaskDisplay: its slot is connected).
  explicit AcknowledgeProperties(rviz::Display* display);
  /// After loading `config`: the values that were unusable and replaced (empty when none). A config
  /// without the group (saved before it existed) loads with Acknowledge off.
  QString checkLoaded(const rviz::Config& config) const;
  AcknowledgeParameters arc() const;
  ClusterLimits clusters() const;
  TrackerParameters tracker() const;
  /// The group is on and names a topic: what to subscribe to (empty: nothing).
  std::string wantedTopic() const;

  rviz::BoolProperty* enabled;          ///< the group "Acknowledge"
  rviz::RosTopicProperty* path_topic;   ///< child: nav_msgs/Path
  rviz::TfFrameProperty* robot_frame;   ///< child
  rviz::FloatProperty* range;           ///< child, metres
  rviz::FloatProperty* distance;        ///< child, metres
  rviz::FloatProperty* arc_angle;       ///< child, degrees
  rviz::FloatProperty* line_width;      ///< child, metres
  rviz::ColorProperty* color;           ///< child
  rviz::FloatProperty* hold;            ///< child, seconds
  rviz::BoolProperty* side_arrow;       ///< child
  rviz::FloatProperty* cluster_gap;     ///< child, metres
  rviz::FloatProperty* min_width;       ///< child, metres
  rviz::FloatProperty* max_width;       ///< child, metres
  rviz::IntProperty* min_points;        ///< child
};
}  // namespace rviz_projector
