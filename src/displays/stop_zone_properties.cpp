#include "rviz_projector/displays/stop_zone_properties.h"

#include <cmath>

#include <nav_msgs/Odometry.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>

#include "rviz_projector/displays/config_check.h"

namespace rviz_projector
{
namespace
{
enum Style
{
  kFilled = 0,
  kHatched = 1,
};
}  // namespace

StopZoneProperties::StopZoneProperties(rviz::Display* display)
{
  const StopZoneParameters defaults;
  enabled = new rviz::BoolProperty(
      "Stop zone", false,
      "A bar across the path where the robot would stop at its current speed (v^2 / (2 Deceleration) + v Reaction "
      "time, the speed from the Odometry topic's twist, smoothed), the floor between the robot and the bar filled or "
      "hatched. Hidden while the robot stands; never drawn beyond the destination.",
      display, SLOT(updateStopZone()), display);
  topic = new rviz::RosTopicProperty(
      "Odometry topic", "", QString::fromStdString(ros::message_traits::datatype<nav_msgs::Odometry>()),
      "nav_msgs/Odometry of the robot's base: the speed is the planar norm of its twist's linear velocity "
      "(hypot(x, y), in child_frame_id). Reversing counts like driving forwards.",
      enabled, SLOT(updateStopZone()), display);
  deceleration = boundedFloat("Deceleration", static_cast<float>(defaults.deceleration), 0.01f, 100.0f,
                              "The robot's braking deceleration, m/s^2.", enabled, display, SLOT(updateStopZone()));
  reaction_time = boundedFloat("Reaction time", static_cast<float>(defaults.reaction_time), 0.0f, 10.0f,
                               "Seconds before braking starts, driven at the current speed.", enabled, display, SLOT(updateStopZone()));
  style = new rviz::EnumProperty("Style", "Filled",
                                 "Filled: the floor between the robot and the bar is one area. Hatched: stripes "
                                 "across the path, 5 cm long every 15 cm from the robot on.",
                                 enabled, SLOT(updateStopZone()), display);
  style->addOption("Filled", kFilled);
  style->addOption("Hatched", kHatched);
  color = new rviz::ColorProperty("Color", QColor(255, 140, 0), "Colour of the zone and its bar.", enabled,
                                  SLOT(updateStopZone()), display);
  alpha = boundedFloat("Alpha", static_cast<float>(defaults.fill_alpha), 0.0f, 1.0f,
                       "Opacity of the filled area or the stripes (times the display's Alpha); the bar is drawn "
                       "with the display's Alpha.",
                       enabled, display, SLOT(updateStopZone()));
  width = boundedFloat("Width", static_cast<float>(defaults.width), 0.01f, 10.0f,
                       "Metres across the path, centred on it.", enabled, display, SLOT(updateStopZone()));
}

QString StopZoneProperties::checkLoaded(const rviz::Config& config) const
{
  ConfigCheck check;
  const rviz::Config group = config.mapGetChild(enabled->getName());
  for (rviz::FloatProperty* p : {deceleration, reaction_time, alpha, width})
  {
    check.number(group.mapGetChild(p->getName()), p);
  }
  check.choice(group.mapGetChild(style->getName()), style, {"Filled", "Hatched"}, "Filled");
  return check.report();
}

StopZoneParameters StopZoneProperties::parameters() const
{
  StopZoneParameters p;
  p.deceleration = decimal(deceleration);
  p.reaction_time = decimal(reaction_time);
  p.width = decimal(width);
  p.hatched = style->getOptionInt() == kHatched;
  p.fill_alpha = decimal(alpha);
  return p;
}

std::string StopZoneProperties::wantedTopic() const
{
  return enabled->getBool() ? topic->getStdString() : std::string();
}
}  // namespace rviz_projector
