#include "rviz_projector/displays/corridor_properties.h"

#include <cmath>

#include <geometry_msgs/PolygonStamped.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/string_property.h>

#include "rviz_projector/displays/config_check.h"

namespace rviz_projector
{
namespace
{
enum Style
{
  kEdges = 0,
  kBand = 1,
};
}  // namespace

CorridorProperties::CorridorProperties(rviz::Display* display)
{
  const CorridorParameters defaults;
  enabled = new rviz::BoolProperty(
      "Corridor", false,
      "The floor the robot will sweep: its footprint moved along the next Length metres of the path from the robot "
      "(where the horizon starts), turning with the path, clipped at the destination; drawn as its two outer edges "
      "or as a band.",
      display, SLOT(updateCorridor()), display);
  footprint = new rviz::EnumProperty(
      "Footprint", "Radius",
      "The robot's outline: a circle of Radius, the Polygon typed here, or a geometry_msgs/PolygonStamped topic "
      "(move_base publishes .../global_costmap/footprint: the outline where the robot is, in any frame; it is "
      "moved into the Robot frame with tf).",
      enabled, SLOT(updateCorridor()), display);
  footprint->addOption("Radius", static_cast<int>(Source::Radius));
  footprint->addOption("Polygon", static_cast<int>(Source::Polygon));
  footprint->addOption("Topic", static_cast<int>(Source::Topic));
  radius = boundedFloat("Radius", 0.3f, 0.01f, 10.0f, "Radius of a round robot, metres (Footprint: Radius).", enabled,
                        display, SLOT(updateCorridor()));
  polygon = new rviz::StringProperty(
      "Polygon", "[[0.4, 0.3], [-0.2, 0.3], [-0.2, -0.3], [0.4, -0.3]]",
      "The robot's outline in the Robot frame (x forwards, y left), metres, as move_base's footprint parameter: "
      "[[x, y], [x, y], ...] (Footprint: Polygon). At least 3 points, edges that do not cross.",
      enabled, SLOT(updateCorridor()), display);
  topic = new rviz::RosTopicProperty(
      "Footprint topic", "", QString::fromStdString(ros::message_traits::datatype<geometry_msgs::PolygonStamped>()),
      "geometry_msgs/PolygonStamped with the robot's outline (Footprint: Topic).", enabled, SLOT(updateCorridor()),
      display);
  length = boundedFloat("Length", static_cast<float>(defaults.length), 0.1f, 100.0f,
                        "Metres of path ahead of the robot that the corridor covers.", enabled, display, SLOT(updateCorridor()));
  style = new rviz::EnumProperty("Style", "Edges",
                                 "Edges: the corridor's two outer edges as lines of Edge width. Band: the swept floor "
                                 "filled with Color at Alpha.",
                                 enabled, SLOT(updateCorridor()), display);
  style->addOption("Edges", kEdges);
  style->addOption("Band", kBand);
  edge_width = boundedFloat("Edge width", static_cast<float>(defaults.edge_width), 0.005f, 1.0f,
                            "Width of the edge lines, metres, centred on the corridor's edge.", enabled, display, SLOT(updateCorridor()));
  color = new rviz::ColorProperty("Color", QColor(255, 200, 0), "Colour of the edges or the band.", enabled,
                                  SLOT(updateCorridor()), display);
  alpha = boundedFloat("Alpha", 0.3f, 0.0f, 1.0f,
                       "Opacity of the band (times the display's Alpha); the edges are drawn with the display's "
                       "Alpha.",
                       enabled, display, SLOT(updateCorridor()));
}

QString CorridorProperties::checkLoaded(const rviz::Config& config) const
{
  ConfigCheck check;
  const rviz::Config group = config.mapGetChild(enabled->getName());
  for (rviz::FloatProperty* p : {radius, length, edge_width, alpha})
  {
    check.number(group.mapGetChild(p->getName()), p);
  }
  check.choice(group.mapGetChild(footprint->getName()), footprint, {"Radius", "Polygon", "Topic"}, "Radius");
  check.choice(group.mapGetChild(style->getName()), style, {"Edges", "Band"}, "Edges");
  return check.report();
}

CorridorParameters CorridorProperties::parameters() const
{
  CorridorParameters p;
  p.length = decimal(length);
  p.edge_width = decimal(edge_width);
  return p;
}

CorridorProperties::Source CorridorProperties::source() const
{
  return static_cast<Source>(footprint->getOptionInt());
}

bool CorridorProperties::band() const
{
  return style->getOptionInt() == kBand;
}

std::string CorridorProperties::wantedTopic() const
{
  return enabled->getBool() && source() == Source::Topic ? topic->getStdString() : std::string();
}
}  // namespace rviz_projector
