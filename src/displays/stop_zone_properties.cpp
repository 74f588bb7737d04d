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
  const SpeedCoding coding;
  speed_coded = new rviz::BoolProperty(
      "Speed-coded spacing", false,
      "Exact spacing only: the arrows are spaced by the speed the robot will have there x Time step (at least Min "
      "spacing) instead of Spacing, so they crowd where it slows down for its destination. The speed is this "
      "group's filtered odometry speed, braking with Deceleration to stop at the destination (min(v, sqrt(2 a d)), "
      "d the path left to the destination); a standing robot gets Min spacing. Marching is not applied then.",
      enabled, SLOT(updateStopZone()), display);
  speed_coded->setDisableChildrenIfFalse(true);
  time_step = boundedFloat("Time step", static_cast<float>(coding.time_step), 0.05f, 10.0f,
                           "Seconds of driving between two arrows (Speed-coded spacing).", speed_coded, display,
                           SLOT(updateStopZone()));
  min_spacing = boundedFloat("Min spacing", static_cast<float>(coding.min_spacing), 0.01f, 10.0f,
                             "Closest two arrows come, metres (Speed-coded spacing).", speed_coded, display,
                             SLOT(updateStopZone()));
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
  const rviz::Config coded = group.mapGetChild(speed_coded->getName());
  for (rviz::FloatProperty* p : {time_step, min_spacing})
  {
    check.number(coded.mapGetChild(p->getName()), p);
  }
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
SpeedCoding StopZoneProperties::speedCoding(double speed) const
{
  SpeedCoding coding;
  coding.enabled = enabled->getBool() && speed_coded->getBool();
  coding.speed = speed;
  coding.deceleration = decimal(deceleration);
  coding.time_step = decimal(time_step);
  coding.min_spacing = decimal(min_spacing);
  return coding;
}
}  // namespace rviz_projector
