#include "rviz_projector/displays/acknowledge_properties.h"

#include <algorithm>
#include <cmath>

#include <nav_msgs/Path.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/tf_frame_property.h>

#include "rviz_projector/displays/config_check.h"

namespace rviz_projector
{
namespace
{
constexpr double kDegrees = M_PI / 180.0;
}  // namespace

AcknowledgeProperties::AcknowledgeProperties(rviz::Display* display)
{
  const AcknowledgeParameters arc_defaults;
  const ClusterLimits cluster_defaults;
  const TrackerParameters tracker_defaults;
  enabled = new rviz::BoolProperty(
      "Acknowledge", false,
      "\"I have seen you\": an arc on the floor on the robot's side of each person (a person-sized cluster of the "
      "scan) within Range of the path ahead, Distance beyond the masked feet, fading out Hold seconds after the "
      "person leaves. The mask still wins: the arc never reaches the person's masked area.",
      display, SLOT(updateAcknowledge()), display);
  path_topic = new rviz::RosTopicProperty(
      "Path topic", "", QString::fromStdString(ros::message_traits::datatype<nav_msgs::Path>()),
      "nav_msgs/Path the robot follows: its part from the point nearest the robot onward is the path ahead.",
      enabled, SLOT(updateAcknowledge()), display);
  robot_frame = new rviz::TfFrameProperty("Robot frame", "base_link",
                                          "The robot's tf frame: where the path ahead starts, and what the arc faces.",
                                          enabled, nullptr, false, SLOT(updateAcknowledge()), display);
  range = boundedFloat("Range", static_cast<float>(arc_defaults.range), 0.0f, 100.0f,
                       "Metres: people whose centre is further than this from the path ahead get no arc.", enabled,
                       display, SLOT(updateAcknowledge()));
  distance = boundedFloat("Distance", static_cast<float>(arc_defaults.distance), 0.0f, 10.0f,
                          "Metres from the edge of the person's masked feet (the cluster's radius + Margin x 1.414) "
                          "to the arc's inner edge.",
                          enabled, display, SLOT(updateAcknowledge()));
  arc_angle = boundedFloat("Arc angle", 120.0f, 1.0f, 360.0f,
                           "Degrees the arc spans, centred on the direction from the person to the robot.", enabled,
                           display, SLOT(updateAcknowledge()));
  line_width = boundedFloat("Line width", static_cast<float>(arc_defaults.line_width), 0.005f, 1.0f,
                            "Metres: the arc's width (and the side arrow's shaft).", enabled, display,
                            SLOT(updateAcknowledge()));
  color = new rviz::ColorProperty("Color", QColor(255, 255, 255), "Colour of the arc and the side arrow.", enabled,
                                  SLOT(updateAcknowledge()), display);
  hold = boundedFloat("Hold", static_cast<float>(tracker_defaults.hold), 0.0f, 60.0f,
                      "Seconds: after a person leaves the scan their arc fades out linearly over this time, then "
                      "goes.",
                      enabled, display, SLOT(updateAcknowledge()));
  side_arrow = new rviz::BoolProperty(
      "Side arrow", false,
      "Also a short arrow beside the person, on the side the path passes them, pointing along the path.", enabled,
      SLOT(updateAcknowledge()), display);
  cluster_gap = boundedFloat("Cluster gap", static_cast<float>(cluster_defaults.gap), 0.01f, 5.0f,
                             "Metres: consecutive scan returns further apart than this belong to different "
                             "clusters.",
                             enabled, display, SLOT(updateAcknowledge()));
  min_width = boundedFloat("Min cluster width", static_cast<float>(cluster_defaults.min_width), 0.0f, 10.0f,
                           "Metres: narrower clusters are no person.", enabled, display, SLOT(updateAcknowledge()));
  max_width = boundedFloat("Max cluster width", static_cast<float>(cluster_defaults.max_width), 0.0f, 10.0f,
                           "Metres: wider clusters (walls, shelves) are no person.", enabled, display,
                           SLOT(updateAcknowledge()));
  min_points = new rviz::IntProperty("Min points", static_cast<int>(cluster_defaults.min_points),
                                     "Clusters of fewer scan returns are no person.", enabled,
                                     SLOT(updateAcknowledge()), display);
  min_points->setMin(1);
  min_points->setMax(100000);
}

QString AcknowledgeProperties::checkLoaded(const rviz::Config& config) const
{
  ConfigCheck check;
  const rviz::Config group = config.mapGetChild(enabled->getName());
  for (rviz::FloatProperty* p :
       {range, distance, arc_angle, line_width, hold, cluster_gap, min_width, max_width})
  {
    check.number(group.mapGetChild(p->getName()), p);
  }
  check.number(group.mapGetChild(min_points->getName()), min_points);
  return check.report();
}

AcknowledgeParameters AcknowledgeProperties::arc() const
{
  AcknowledgeParameters p;
  p.range = decimal(range);
  p.distance = decimal(distance);
  p.arc_angle = decimal(arc_angle) * kDegrees;
  p.line_width = decimal(line_width);
  p.side_arrow = side_arrow->getBool();
  return p;
}

ClusterLimits AcknowledgeProperties::clusters() const
{
  ClusterLimits l;
  l.gap = decimal(cluster_gap);
  l.min_width = decimal(min_width);
  l.max_width = decimal(max_width);
  l.min_points = static_cast<std::size_t>(std::max(1, min_points->getInt()));
  return l;
}

TrackerParameters AcknowledgeProperties::tracker() const
{
  TrackerParameters t;
  t.hold = decimal(hold);
  return t;
}

std::string AcknowledgeProperties::wantedTopic() const
{
  return enabled->getBool() ? path_topic->getStdString() : std::string();
}
}  // namespace rviz_projector
