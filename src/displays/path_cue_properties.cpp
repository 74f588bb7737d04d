#include "rviz_projector/displays/path_cue_properties.h"

#include <cmath>

#include <actionlib_msgs/GoalStatusArray.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/tf_frame_property.h>

#include "rviz_projector/displays/config_check.h"

namespace rviz_projector
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

/// `config`'s entry for `child` of the group `group` (rviz saves a property with children as a
/// map: its own value under "Value", each child under its name).
rviz::Config childConfig(const rviz::Config& config, const rviz::Property* group, const rviz::Property* child)
{
  return config.mapGetChild(group->getName()).mapGetChild(child->getName());
}
}  // namespace

PathCueProperties::PathCueProperties(rviz::Display* display)
{
  const PathCueSettings defaults;
  const GoalCueParameters goal_defaults;
  robot_frame = new rviz::TfFrameProperty(
      "Robot frame", "base_link",
      "The robot's tf frame: where the horizon, the stop zone, the corridor and the off-view cue start (its heading: the off-view cue's turn in place), where the turn signal is drawn, and whether the robot stands "
      "still (pre-motion warning).",
      display, nullptr, false, SLOT(updateCues()), display);

  horizon = new rviz::BoolProperty(
      "Horizon", false,
      "Draw only the next metres of path from the robot, the last metre fading out: the floor shows what is "
      "imminent, not the whole route.",
      display, SLOT(updateCues()), display);
  horizon_length = boundedFloat("Length", static_cast<float>(defaults.horizon_length), 0.0f, 1000.0f,
                                "Metres of path ahead of the robot that are drawn.", horizon, display, SLOT(updateCues()));
  fade_length = boundedFloat("Fade", static_cast<float>(defaults.fade_length), 0.0f, 1000.0f,
                             "The last metres of the horizon fade out (opacity falls linearly to 0). With a cue "
                             "on, arrows are drawn Flat (Style 3D is not used).",
                             horizon, display, SLOT(updateCues()));

  marching = new rviz::BoolProperty(
      "Marching", false,
      "Arrows move along the path towards the destination and re-enter at the start (Spacing mode Exact). Their "
      "places depend only on the path and ROS time: a replan of the same route changes nothing.",
      display, SLOT(updateCues()), display);
  marching_speed = boundedFloat("Speed", static_cast<float>(defaults.marching_speed), 0.0f, 10.0f,
                                "Marching speed, m/s.", marching, display, SLOT(updateCues()));

  state_topic = new rviz::RosTopicProperty(
      "State topic", "",
      QString::fromStdString(ros::message_traits::datatype<actionlib_msgs::GoalStatusArray>()),
      "actionlib_msgs/GoalStatusArray of the navigation goal (e.g. /move_base/status): a failed goal hides the arrows "
      "and marks the destination with a cross, a reached goal flashes the destination once, then clears. Empty: the "
      "goal's state changes nothing.",
      display, SLOT(updateStateTopic()), display);
  failed_color = new rviz::ColorProperty("Failed color", QColor(255, 0, 0),
                                         "Colour of the cross at the destination of a preempted, aborted or rejected "
                                         "goal.",
                                         state_topic, SLOT(updateCues()), display);
  succeeded_color = new rviz::ColorProperty("Succeeded color", QColor(255, 255, 255),
                                            "Colour of the destination's flash when the goal is reached.",
                                            state_topic, SLOT(updateCues()), display);
  warning = new rviz::BoolProperty(
      "Pre-motion warning", false,
      "When a new goal becomes active while the robot stands still, path and destination blink for at least the "
      "Warning time before they become steady. The visual half of a start warning: it does not hold the robot.",
      state_topic, SLOT(updateCues()), display);
  warning_time = boundedFloat("Warning time", static_cast<float>(goal_defaults.warning_time), 0.0f, 60.0f,
                              "Seconds of blinking.", warning, display, SLOT(updateCues()));
  warning_hz = boundedFloat("Blink frequency", static_cast<float>(goal_defaults.warning_hz), 0.1f, 10.0f,
                            "Blinks per second during the warning.", warning, display, SLOT(updateCues()));

  turn_signal = new rviz::BoolProperty(
      "Turn signal", false,
      "A curved arrow on the floor in front of the robot (see Glyph ahead), beside the path on the inside of a "
      "coming sharp turn, blinking at 1.5 Hz like a car's indicator.",
      display, SLOT(updateCues()), display);
  turn_angle = boundedFloat("Turn angle", static_cast<float>(defaults.turn.angle * 180.0 / kPi), 1.0f, 360.0f,
                            "Degrees: a turn of the path sharper than this is signalled.", turn_signal, display, SLOT(updateCues()));
  turn_distance = boundedFloat("Turn distance", static_cast<float>(defaults.turn.distance), 0.0f, 100.0f,
                               "Metres of path ahead of the robot in which a turn is signalled.", turn_signal, display, SLOT(updateCues()));
  glyph_size = boundedFloat("Glyph size", static_cast<float>(defaults.glyph_size), 0.01f, 10.0f,
                            "Metres across the turn-signal glyph.", turn_signal, display, SLOT(updateCues()));
  glyph_ahead = boundedFloat("Glyph ahead", static_cast<float>(defaults.glyph_ahead), -10.0f, 10.0f,
                             "Metres in front of the robot's centre (along the path's direction at the robot) "
                             "where the glyph is drawn, beside the path: where a projector on the robot lights the "
                             "floor.",
                             turn_signal, display, SLOT(updateCues()));
}

QString PathCueProperties::checkLoaded(const rviz::Config& config) const
{
  ConfigCheck check;
  for (rviz::FloatProperty* p : {horizon_length, fade_length})
  {
    check.number(childConfig(config, horizon, p), p);
  }
  check.number(childConfig(config, marching, marching_speed), marching_speed);
  for (rviz::FloatProperty* p : {turn_angle, turn_distance, glyph_size, glyph_ahead})
  {
    check.number(childConfig(config, turn_signal, p), p);
  }
  const rviz::Config warning_config = config.mapGetChild(state_topic->getName()).mapGetChild(warning->getName());
  for (rviz::FloatProperty* p : {warning_time, warning_hz})
  {
    check.number(warning_config.mapGetChild(p->getName()), p);
  }
  return check.report();
}

PathCueSettings PathCueProperties::settings() const
{
  PathCueSettings s;
  s.horizon = horizon->getBool();
  s.horizon_length = decimal(horizon_length);
  s.fade_length = decimal(fade_length);
  s.marching = marching->getBool();
  s.marching_speed = decimal(marching_speed);
  s.turn_signal = turn_signal->getBool();
  s.turn.angle = decimal(turn_angle) * kPi / 180.0;
  s.turn.distance = decimal(turn_distance);
  s.glyph_size = decimal(glyph_size);
  s.glyph_ahead = decimal(glyph_ahead);
  s.glyph_aside = 0.3 + 0.5 * s.glyph_size;  // beside the path's arrows, not on them
  return s;
}

GoalCueParameters PathCueProperties::goalParameters() const
{
  GoalCueParameters p;
  p.warning_enabled = warning->getBool();
  p.warning_time = decimal(warning_time);
  p.warning_hz = decimal(warning_hz);
  return p;
}
}  // namespace rviz_projector
