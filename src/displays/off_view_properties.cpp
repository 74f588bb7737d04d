#include "rviz_projector/displays/off_view_properties.h"

#include <sensor_msgs/CameraInfo.h>
#include <rviz/config.h>
#include <rviz/display.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>

#include "rviz_projector/displays/config_check.h"

namespace rviz_projector
{
namespace
{
/// The arrow's head width and the digits' height, as fractions of Arrow size (the core's defaults:
/// 0.12 and 0.1 for a 0.3 m arrow).
constexpr double kWidthPerSize = 0.4;
constexpr double kDigitsPerSize = 1.0 / 3.0;
}  // namespace

OffViewProperties::OffViewProperties(rviz::Display* display)
{
  const OffViewParameters defaults;
  enabled = new rviz::BoolProperty(
      "Off-view cue", false,
      "When the path's next Look-ahead metres leave the projector's lit area (on the last metre to a goal, while "
      "the robot turns in place), a cue inside the lit area: an arrow at its edge pointing where the path goes, a "
      "turn-in-place glyph, or on the final approach an arrow towards the destination with its distance. Never on "
      "arrows that are in view; gone as soon as the path is visible again.",
      display, SLOT(updateOffView()), display);
  topic = new rviz::RosTopicProperty(
      "Projector info topic", "", QString::fromStdString(ros::message_traits::datatype<sensor_msgs::CameraInfo>()),
      "sensor_msgs/CameraInfo of the projector (the ProjectorCamera's Topic): its lens, at the tf pose of the "
      "header's frame_id, gives the lit area on the floor.",
      enabled, SLOT(updateOffView()), display);
  look_ahead = boundedFloat("Look-ahead", static_cast<float>(defaults.look_ahead), 0.1f, 100.0f,
                            "Metres of path ahead of the robot that are judged: a cue appears when less than a "
                            "quarter of them is in the lit area, and goes once 40 % are.",
                            enabled, display, SLOT(updateOffView()));
  final_approach = boundedFloat("Final approach", static_cast<float>(defaults.final_approach), 0.0f, 100.0f,
                                "With at most this much path left (metres) and the destination outside the lit "
                                "area, the cue points at the destination and shows its distance.",
                                enabled, display, SLOT(updateOffView()));
  size = boundedFloat("Arrow size", static_cast<float>(defaults.arrow_length), 0.05f, 2.0f,
                      "Length of the cue's arrow and size of its turn-in-place glyph, metres (head width 0.4 of it, "
                      "digits a third of it).",
                      enabled, display, SLOT(updateOffView()));
  color = new rviz::ColorProperty("Color", QColor(0, 200, 255), "Colour of the cue.", enabled, SLOT(updateOffView()),
                                  display);
  alpha = boundedFloat("Alpha", 1.0f, 0.0f, 1.0f, "Opacity of the cue (times the display's Alpha).", enabled,
                       display, SLOT(updateOffView()));
}

QString OffViewProperties::checkLoaded(const rviz::Config& config) const
{
  ConfigCheck check;
  const rviz::Config group = config.mapGetChild(enabled->getName());
  for (rviz::FloatProperty* p : {look_ahead, final_approach, size, alpha})
  {
    check.number(group.mapGetChild(p->getName()), p);
  }
  return check.report();
}

OffViewParameters OffViewProperties::parameters() const
{
  OffViewParameters p;
  p.look_ahead = decimal(look_ahead);
  p.final_approach = decimal(final_approach);
  const double s = decimal(size);
  p.arrow_length = s;
  p.arrow_width = kWidthPerSize * s;
  p.glyph_size = s;
  p.digit_height = kDigitsPerSize * s;
  return p;
}

std::string OffViewProperties::wantedTopic() const
{
  return enabled->getBool() ? topic->getStdString() : std::string();
}
}  // namespace rviz_projector
