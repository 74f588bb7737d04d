// ProjectedPathDisplay, its cue animation (the other half, projected_path_display.cpp: messages,
// spacing, drawing without cues): the cue settings and State topic, the cue timeline advanced for
// each frame's ROS time (ProjectionAnimation: the projector ticks it before a frame, rviz's update
// for the main view), drawn only when the picture changed.
#include <algorithm>
#include <cmath>
#include <utility>

#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/status_property.h>
#include <rviz/properties/tf_frame_property.h>

#include "rviz_projector/core/marching.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/displays/path_cue_properties.h"
#include "rviz_projector/displays/projected_path_display.h"
#include "rviz_projector/displays/projection_change_notifier.h"
#include "rviz_projector/displays/ros_clock.h"
#include "rviz_projector/displays/corridor_properties.h"
#include "rviz_projector/displays/off_view_properties.h"
#include "rviz_projector/displays/stop_zone_properties.h"

namespace rviz_projector
{
ros::Time ProjectedPathDisplay::cueTime()
{
  // The cue timelines run on ROS time (a bag at half rate animates at half speed): the shared clock.
  return ros::Time(std::max(0.0, RosClock::shared().tick().rosNow()));
}

void ProjectedPathDisplay::checkSpacingCombinations()
{
  if (cue_settings_.marching && mode_property_->getOptionInt() == static_cast<int>(SpacingMode::Paper))
  {
    setStatus(rviz::StatusProperty::Warn, "Marching", "Marching needs Spacing mode Exact: the arrows stand still");
  }
  else if (cue_settings_.marching && spacer_.parameters().speed_coding.enabled)
  {
    setStatus(rviz::StatusProperty::Warn, "Marching",
              "Marching is not applied with Stop zone > Speed-coded spacing: the arrows stand still");
  }
  else
  {
    deleteStatus("Marching");
  }
  if (spacer_.parameters().speed_coding.enabled && spacer_.parameters().mode == SpacingMode::Paper)
  {
    setStatus(rviz::StatusProperty::Warn, "Speed-coded spacing",
              "Speed-coded spacing needs Spacing mode Exact: the arrows keep Spacing");
  }
  else
  {
    deleteStatus("Speed-coded spacing");
  }
}

bool ProjectedPathDisplay::cuesActive() const
{
  return cue_settings_.horizon || cue_settings_.marching || cue_settings_.turn_signal || cue_settings_.stop_zone ||
         cue_settings_.corridor || cue_settings_.off_view || cue_source_.subscribed();
}

void ProjectedPathDisplay::updateCues()
{
  cue_settings_ = cue_properties_->settings();
  cue_settings_.stop_zone = stop_properties_->enabled->getBool();
  cue_settings_.stop = stop_properties_->parameters();
  cue_settings_.corridor = corridor_properties_->enabled->getBool();
  cue_settings_.corridor_parameters = corridor_properties_->parameters();
  cue_settings_.off_view = off_view_properties_->enabled->getBool();
  cue_source_.setParameters(cue_properties_->goalParameters());
  if (!stop_properties_->speedCoding(0.0).enabled)
  {
    coded_speed_ = 0.0;
  }
  spacer_.setParameters(spacingParameters());
  checkSpacingCombinations();
  if (!cuesActive() && arrow_mesh_)
  {
    robot_status_shown_ = CueStatus();
    deleteStatus("Robot");
  }
  rebuild();  // re-spaced (a marching phase) and drawn with the new settings at once
}

void ProjectedPathDisplay::updateStateTopic()
{
  if (!initialized())
  {
    return;
  }
  cue_source_.subscribe(update_nh_, cue_properties_->state_topic->getStdString());
  state_status_shown_ = CueStatus();
  deleteStatus("State");
  showCueStatus("State", cue_source_.stateStatus(), state_status_shown_);  // e.g. an invalid topic name
  updateCues();
}

void ProjectedPathDisplay::updateStopZone()
{
  if (!initialized())
  {
    return;
  }
  stop_source_.subscribe(update_nh_, stop_properties_->wantedTopic());
  stop_status_shown_ = CueStatus();
  deleteStatus("Stop zone");
  if (stop_properties_->enabled->getBool())
  {
    showCueStatus("Stop zone", stop_source_.status(cueTime().toSec()), stop_status_shown_);
  }
  updateCues();
}

void ProjectedPathDisplay::updateCorridor()
{
  if (!initialized())
  {
    return;
  }
  corridor_source_.subscribe(update_nh_, corridor_properties_->wantedTopic());
  // A Radius or a typed Polygon only changes with the properties: read here, not every frame.
  if (corridor_properties_->source() == CorridorProperties::Source::Radius)
  {
    corridor_typed_ = CorridorSource::fromRadius(corridor_properties_->radius->getFloat());
  }
  else if (corridor_properties_->source() == CorridorProperties::Source::Polygon)
  {
    corridor_typed_ = CorridorSource::fromText(corridor_properties_->polygon->getStdString());
  }
  corridor_status_shown_ = CueStatus();
  deleteStatus("Corridor");
  updateCues();
}

void ProjectedPathDisplay::updateOffView()
{
  if (!initialized())
  {
    return;
  }
  off_view_source_.subscribe(update_nh_, off_view_properties_->wantedTopic());
  off_view_source_.resetCue();  // new parameters: judged afresh
  off_view_status_shown_ = CueStatus();
  deleteStatus("Off-view cue");
  updateCues();
}

void ProjectedPathDisplay::buildOffView(const PathCueInput& input)
{
  off_view_next_.clear();
  if (!cue_settings_.off_view)
  {
    return;
  }
  if (!input.goal.arrows)
  {
    // The arrows are not shown (the goal's state hides them): neither is what stands for them.
    off_view_source_.resetCue();
    showCueStatus("Off-view cue", CueStatus{CueStatus::Level::Ok, "Nothing drawn: the arrows are hidden"},
                  off_view_status_shown_);
    return;
  }
  OffViewInput robot;
  robot.robot = input.robot;
  robot.heading = input.heading;
  robot.start = cue_next_.robotArc();
  // The cue keeps clear of the arrows that are drawn: from the horizon's start with the horizon on.
  robot.drawn_from = cue_settings_.horizon ? cue_next_.horizonStart() : 0.0;
  const OffViewResult& cue =
      off_view_source_.cueAt(*context_->getFrameManager(), last_msg_.get(), floor_points_, cue_next_.lengths(),
                             input.robot_known, robot, off_view_properties_->parameters());
  off_view_next_.assign(cue.triangles.begin(), cue.triangles.end());
  showCueStatus("Off-view cue", off_view_source_.status(), off_view_status_shown_);
}

void ProjectedPathDisplay::takeCorridorFootprint()
{
  CorridorFootprint from_topic;
  if (corridor_properties_->source() == CorridorProperties::Source::Topic)
  {
    from_topic = corridor_source_.fromTopic(*context_->getTF2BufferPtr(), cue_properties_->robot_frame->getFrameStd());
  }
  const CorridorFootprint& footprint =
      corridor_properties_->source() == CorridorProperties::Source::Topic ? from_topic : corridor_typed_;
  showCueStatus("Corridor", footprint.status, corridor_status_shown_);
  // Nothing usable: radius 0 and no polygon, which CueDrawing sweeps as nothing.
  cue_settings_.corridor_radius = footprint.usable() ? footprint.radius : 0.0;
  if (footprint.usable())
  {
    cue_settings_.corridor_footprint = footprint.polygon;
  }
  else
  {
    cue_settings_.corridor_footprint.clear();
  }
}

void ProjectedPathDisplay::update(float /*wall_dt*/, float /*ros_dt*/)
{
  advance(cueTime());  // the main view animates without a projector too
}

void ProjectedPathDisplay::advance(const ros::Time& now)
{
  if (!arrow_mesh_ || !isEnabled() || !last_msg_ || !cuesActive() || now == last_advance_)
  {
    return;  // two projectors tick at the same time: drawn once
  }
  drawCues(now, false);
}

void ProjectedPathDisplay::showCueStatus(const QString& name, const CueStatus& status, CueStatus& shown)
{
  if (status.level == shown.level && status.text == shown.text)
  {
    return;  // statuses change rarely; this runs at the frame rate
  }
  shown = status;
  if (status.text.empty())
  {
    deleteStatus(name);
    return;
  }
  const rviz::StatusProperty::Level level = status.level == CueStatus::Level::Ok     ? rviz::StatusProperty::Ok
                                            : status.level == CueStatus::Level::Warn ? rviz::StatusProperty::Warn
                                                                                     : rviz::StatusProperty::Error;
  setStatus(level, name, QString::fromStdString(status.text));
}

void ProjectedPathDisplay::drawCues(const ros::Time& now, bool force)
{
  last_advance_ = now;
  PathCueInput input = cue_source_.inputAt(now, *context_->getFrameManager(),
                                           cue_properties_->robot_frame->getFrameStd(), cue_settings_.needsRobot());
  showCueStatus("Robot", cue_source_.robotStatus(), robot_status_shown_);
  showCueStatus("State", cue_source_.stateStatus(), state_status_shown_);
  if (cue_settings_.corridor)
  {
    takeCorridorFootprint();
  }
  if (cue_settings_.stop_zone)
  {
    input.speed = stop_source_.speedAt(input.time);
    showCueStatus("Stop zone", stop_source_.status(input.time), stop_status_shown_);
  }
  bool respace = false;
  if (spacer_.parameters().speed_coding.enabled)
  {
    // In 1 cm/s steps: the filtered speed changes every frame, the arrows only when it really does.
    const double speed = input.speed.moving ? std::round(input.speed.speed * 100.0) / 100.0 : 0.0;
    if (speed != coded_speed_)
    {
      coded_speed_ = speed;
      spacer_.setParameters(spacingParameters());
      respace = true;
    }
  }
  if (!last_msg_)
  {
    return;
  }
  const SpacingParameters& parameters = spacer_.parameters();
  // Marching needs Exact spacing (a Marching warning says so otherwise): no re-spacing per frame then.
  const double phase = cue_settings_.marching && parameters.mode == SpacingMode::Exact && !parameters.speed_coding.enabled
                           ? marchingPhase(cue_settings_.marching_speed, input.time, parameters.spacing)
                           : 0.0;
  if (respace || phase != spaced_phase_)
  {
    spaced_ = &spacer_.space(floor_points_, phase);
    spaced_phase_ = phase;
  }
  cue_next_.build(floor_points_, *spaced_, parameters, cue_settings_, input);
  buildOffView(input);
  const auto same = [](const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const Vec2& p, const Vec2& q) {
             return p.x == q.x && p.y == q.y;
           });
  };
  if (!force && input.goal.colour == cue_colour_drawn_ && cue_next_.cross() == cue_drawn_.cross() &&
      cue_next_.destinationAlpha() == cue_drawn_.destinationAlpha() &&
      cue_next_.arrowAlpha() == cue_drawn_.arrowAlpha() && same(cue_next_.arrows(), cue_drawn_.arrows()) &&
      same(cue_next_.destination(), cue_drawn_.destination()) && same(cue_next_.glyph(), cue_drawn_.glyph()) &&
      same(cue_next_.stopZone().triangles(), cue_drawn_.stopZone().triangles()) &&
      cue_next_.stopZone().alpha() == cue_drawn_.stopZone().alpha() &&
      same(cue_next_.corridor().band(), cue_drawn_.corridor().band()) &&
      same(cue_next_.corridor().edges(), cue_drawn_.corridor().edges()) && same(off_view_next_, off_view_drawn_))
  {
    return;  // the projector already shows exactly this: no upload, no frame
  }
  std::swap(cue_next_, cue_drawn_);
  off_view_next_.swap(off_view_drawn_);
  cue_colour_drawn_ = input.goal.colour;
  const double height = height_property_->getFloat();
  const float alpha = alpha_property_->getFloat();
  Ogre::ColourValue arrow_colour = arrow_color_property_->getOgreColor();
  arrow_colour.a = alpha;
  Ogre::ColourValue destination_colour =
      input.goal.colour == GoalCueFrame::Colour::Failed      ? cue_properties_->failed_color->getOgreColor()
      : input.goal.colour == GoalCueFrame::Colour::Succeeded ? cue_properties_->succeeded_color->getOgreColor()
                                                              : circle_color_property_->getOgreColor();
  destination_colour.a = alpha * cue_drawn_.destinationAlpha();
  arrow_mesh_->setFlatTriangles(cue_drawn_.arrows(), cue_drawn_.arrowAlpha(), height + kArrowLift, arrow_colour);
  circle_mesh_->setFlatTriangles(cue_drawn_.destination(), height, destination_colour);
  glyph_mesh_->setFlatTriangles(cue_drawn_.glyph(), height + kArrowLift, arrow_colour);
  Ogre::ColourValue stop_colour = stop_properties_->color->getOgreColor();
  stop_colour.a = alpha;
  stop_mesh_->setFlatTriangles(cue_drawn_.stopZone().triangles(), cue_drawn_.stopZone().alpha(), height, stop_colour);
  Ogre::ColourValue corridor_colour = corridor_properties_->color->getOgreColor();
  const bool band = corridor_properties_->band();
  corridor_colour.a = alpha * (band ? corridor_properties_->alpha->getFloat() : 1.0f);
  corridor_mesh_->setFlatTriangles(band ? cue_drawn_.corridor().band() : cue_drawn_.corridor().edges(), height,
                                   corridor_colour);
  Ogre::ColourValue off_view_colour = off_view_properties_->color->getOgreColor();
  off_view_colour.a = alpha * off_view_properties_->alpha->getFloat();
  off_view_mesh_->setFlatTriangles(off_view_drawn_, height + kArrowLift, off_view_colour);
  ++mesh_builds_;
  ProjectionChangeNotifier::notify();
  context_->queueRender();
}

// The cue meshes' sizes, for tests and tools.
std::size_t ProjectedPathDisplay::glyphTriangleCount() const
{
  return glyph_mesh_ ? glyph_mesh_->triangleCount() : 0;
}

std::size_t ProjectedPathDisplay::corridorTriangleCount() const
{
  return corridor_mesh_ ? corridor_mesh_->triangleCount() : 0;
}

std::size_t ProjectedPathDisplay::offViewTriangleCount() const
{
  return off_view_mesh_ ? off_view_mesh_->triangleCount() : 0;
}

std::size_t ProjectedPathDisplay::stopZoneTriangleCount() const
{
  return stop_mesh_ ? stop_mesh_->triangleCount() : 0;
}
}  // namespace rviz_projector
