#include "rviz_projector/displays/projected_path_display.h"

#include <cmath>

#include <OgreSceneManager.h>
#include <OgreSceneNode.h>

#include <rviz/config.h>
#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/status_property.h>
#include <rviz/properties/tf_frame_property.h>

#include "rviz_projector/core/data_age.h"
#include "rviz_projector/core/path_style_limits.h"
#include "rviz_projector/displays/config_check.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/displays/path_cue_properties.h"
#include "rviz_projector/displays/projection_change_notifier.h"
#include "rviz_projector/displays/ros_clock.h"
#include "rviz_projector/displays/corridor_properties.h"
#include "rviz_projector/displays/off_view_properties.h"
#include "rviz_projector/displays/stop_zone_properties.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
enum Style
{
  kFlat = 0,
  kSolid = 1,
};

rviz::FloatProperty* sizeProperty(const QString& name, float value, const QString& description,
                                  rviz::Property* parent, const char* slot, QObject* receiver)
{
  auto* property = new rviz::FloatProperty(name, value, description, parent, slot, receiver);
  property->setMin(static_cast<float>(path_style::kMinSize));
  property->setMax(static_cast<float>(path_style::kMaxSize));
  return property;
}
}  // namespace

ProjectedPathDisplay::ProjectedPathDisplay() : spaced_(&empty_)
{
  // Not yet initialised: set the default without triggering a resubscription.
  topic_property_->blockSignals(true);
  topic_property_->setValue(kDefaultTopic);
  topic_property_->blockSignals(false);
  const SpacingParameters defaults;

  mode_property_ = new rviz::EnumProperty(
      "Spacing mode", "Exact",
      "Exact: arrows every Spacing metres of path, measured back from the destination (steady while "
      "the robot drives). Paper: Algorithm 1 of Han et al. (HRI 2022), arrows between pairs of "
      "path poses at least Spacing apart.",
      this, SLOT(updateSpacing()), this);
  mode_property_->addOption("Exact", static_cast<int>(SpacingMode::Exact));
  mode_property_->addOption("Paper", static_cast<int>(SpacingMode::Paper));

  spacing_property_ = new rviz::FloatProperty(
      "Spacing", static_cast<float>(defaults.spacing),
      "Exact: path length from one arrow tip to the next, metres. Paper: minimum distance between the "
      "path poses that arrows join, metres.",
      this, SLOT(updateSpacing()), this);
  spacing_property_->setMin(static_cast<float>(path_style::kMinSpacing));
  spacing_property_->setMax(static_cast<float>(path_style::kMaxSpacing));

  shaft_length_property_ = sizeProperty("Shaft length", static_cast<float>(defaults.arrow.shaft_length),
                                        "Length of an arrow's shaft, metres (Exact mode; in Paper mode "
                                        "the shaft fills the space between the joined poses).",
                                        this, SLOT(updateSpacing()), this);
  shaft_diameter_property_ = sizeProperty("Shaft diameter", static_cast<float>(defaults.arrow.shaft_diameter),
                                          "Width of an arrow's shaft, metres.", this, SLOT(updateSpacing()), this);
  head_length_property_ = sizeProperty("Head length", static_cast<float>(defaults.arrow.head_length),
                                       "Length of an arrow's head, metres.", this, SLOT(updateSpacing()), this);
  head_diameter_property_ = sizeProperty("Head diameter", static_cast<float>(defaults.arrow.head_diameter),
                                         "Width of an arrow's head at its base, metres.", this,
                                         SLOT(updateSpacing()), this);
  circle_diameter_property_ = sizeProperty(
      "Destination circle diameter", static_cast<float>(defaults.circle_diameter),
      "Diameter of the filled circle drawn at the path's destination, metres.", this, SLOT(updateSpacing()), this);

  arrow_color_property_ = new rviz::ColorProperty("Arrow color", QColor(255, 0, 255), "Colour of the arrows.",
                                                  this, SLOT(updateAppearance()), this);
  circle_color_property_ = new rviz::ColorProperty("Circle color", QColor(0, 255, 0),
                                                   "Colour of the destination circle.", this,
                                                   SLOT(updateAppearance()), this);
  alpha_property_ = new rviz::FloatProperty("Alpha", static_cast<float>(path_style::kDefaultAlpha), "Opacity: 1 is opaque, 0 invisible.", this,
                                            SLOT(updateAppearance()), this);
  alpha_property_->setMin(0.0f);
  alpha_property_->setMax(1.0f);
  height_property_ = new rviz::FloatProperty(
      "Height above floor", static_cast<float>(path_style::kDefaultHeight),
      "Height of the drawing above z = 0 of the fixed frame, metres (a little lift avoids fighting "
      "with a grid or map on the floor).",
      this, SLOT(updateAppearance()), this);
  height_property_->setMin(static_cast<float>(-path_style::kMaxHeight));
  height_property_->setMax(static_cast<float>(path_style::kMaxHeight));

  style_property_ = new rviz::EnumProperty(
      "Style", "Flat",
      "Flat: unlit filled outlines in exactly the chosen colours (what a projector should show). "
      "3D: shaded shaft cylinders and head cones.",
      this, SLOT(updateAppearance()), this);
  style_property_->addOption("Flat", kFlat);
  style_property_->addOption("3D", kSolid);

  path_timeout_property_ = new rviz::FloatProperty(
      "Path timeout", 0.0f,
      "Seconds: when no new path arrived for this long, the arrows and the destination circle are "
      "cleared (the projector shows nothing of this path) until the next one. Counted from when the "
      "message arrived, not from its header stamp. 0: never.",
      this, SLOT(checkPathTimeout()), this);
  path_timeout_property_->setMin(0.0f);
  cue_properties_ = std::make_unique<PathCueProperties>(this);
  stop_properties_ = std::make_unique<StopZoneProperties>(this);
  corridor_properties_ = std::make_unique<CorridorProperties>(this);
  off_view_properties_ = std::make_unique<OffViewProperties>(this);
  cue_settings_ = cue_properties_->settings();
  ProjectionAnimation::add(this);
}

ProjectedPathDisplay::~ProjectedPathDisplay()
{
  ProjectionAnimation::remove(this);
  pauseDraining();
  cue_source_.unsubscribe();
  stop_source_.unsubscribe();
  corridor_source_.unsubscribe();
  off_view_source_.unsubscribe();
}

void ProjectedPathDisplay::onInitialize()
{
  attach(update_nh_);  // before the base class creates subscriber and filter
  MFDClass::onInitialize();
  // Drained while enabled (onEnable starts the timer, onDisable stops it).
  setDrainHandler([this] { drainQueue(); });
  // Sees every message before the tf filter holds it back, to say at once why nothing is drawn.
  // As a MessageEvent (the connection header says whether the publisher latches); message_filters
  // hands a bound callback a bare ConstPtr unless told the parameter type.
  sub_.registerCallback<const ros::MessageEvent<nav_msgs::Path const>&>(
      boost::bind(&ProjectedPathDisplay::checkFrame, this, boost::placeholders::_1));
  arrow_mesh_ = std::make_unique<FloorMesh>(scene_manager_, scene_node_);
  circle_mesh_ = std::make_unique<FloorMesh>(scene_manager_, scene_node_);
  glyph_mesh_ = std::make_unique<FloorMesh>(scene_manager_, scene_node_);
  stop_mesh_ = std::make_unique<FloorMesh>(scene_manager_, scene_node_);
  corridor_mesh_ = std::make_unique<FloorMesh>(scene_manager_, scene_node_);
  off_view_mesh_ = std::make_unique<FloorMesh>(scene_manager_, scene_node_);
  // Bottom to top where they overlap: corridor, stop zone, destination, arrows, glyph, off-view cue
  // (which keeps off the arrows drawn, but lies on the corridor or stop zone when they fill the lit area).
  corridor_mesh_->setLayer(1);
  stop_mesh_->setLayer(2);
  circle_mesh_->setLayer(3);
  arrow_mesh_->setLayer(4);
  glyph_mesh_->setLayer(5);
  off_view_mesh_->setLayer(6);
  cue_properties_->robot_frame->setFrameManager(context_->getFrameManager());
  spacer_.setParameters(spacingParameters());
  updateStateTopic();
  updateStopZone();
  updateCorridor();
  updateOffView();
  setStatus(rviz::StatusProperty::Warn, "Path", "No path received yet");
}

void ProjectedPathDisplay::onEnable()
{
  MFDClass::onEnable();
  resumeDraining();
  scene_node_->setVisible(true);
  for (FloorMesh* mesh : {arrow_mesh_.get(), circle_mesh_.get(), glyph_mesh_.get(), stop_mesh_.get(), corridor_mesh_.get(),
                          off_view_mesh_.get()})
  {
    if (mesh)
    {
      mesh->setShown(true);
    }
  }
  ProjectionChangeNotifier::notify();
}

void ProjectedPathDisplay::onDisable()
{
  MFDClass::onDisable();
  after_jump_.forget();  // enabled again later, only new plans are drawn
  pauseDraining();  // nothing to drain: no subscription while disabled
  scene_node_->setVisible(false);
  for (FloorMesh* mesh : {arrow_mesh_.get(), circle_mesh_.get(), glyph_mesh_.get(), stop_mesh_.get(), corridor_mesh_.get(),
                          off_view_mesh_.get()})
  {
    if (mesh)
    {
      mesh->setShown(false);  // a property changed while disabled must not show a new upload
    }
  }
  ProjectionChangeNotifier::notify();
}

void ProjectedPathDisplay::reset()
{
  if (!initialized())
  {
    return;
  }
  // rviz resets every display a frame after ROS time jumps back (a bag looping): a plan of the new
  // timeline received meanwhile goes through the tf filter again (PathAfterJump).
  const nav_msgs::Path::ConstPtr again = isEnabled() ? after_jump_.retake(RosClock::shared().tick()) : nullptr;
  MFDClass::reset();
  last_msg_.reset();
  floor_points_.clear();
  dropped_poses_ = 0;
  spaced_ = &empty_;
  if (arrow_mesh_)
  {
    arrow_mesh_->clear();
    circle_mesh_->clear();
    glyph_mesh_->clear();
    stop_mesh_->clear();
    corridor_mesh_->clear();
    off_view_mesh_->clear();
    off_view_drawn_.clear();
    ProjectionChangeNotifier::notify();
  }
  cue_source_.clear();
  stop_source_.forgetLaterThan(RosClock::shared().policy().rosNow());
  corridor_source_.clear();
  off_view_source_.resetCue();  // the lens stays: a latched CameraInfo does not come again
  // rviz's Reset cleared every status: each is shown again when next worked out.
  robot_status_shown_ = CueStatus();
  state_status_shown_ = CueStatus();
  stop_status_shown_ = CueStatus();
  corridor_status_shown_ = CueStatus();
  off_view_status_shown_ = CueStatus();
  setStatus(rviz::StatusProperty::Warn, "Path", "No path received yet");
  // rviz's Reset (also at every backward jump of ROS time: a bag loop): a plan from a latched
  // publisher comes back only by subscribing again. A planner that publishes unlatched keeps its
  // subscription: subscribing again would lose every plan sent before the new connection stands
  // (about 0.2 s: the first plan of each bag loop).
  if (isEnabled() && sub_.getSubscriber() && latched_publisher_)
  {
    unsubscribe();
    subscribe();
  }
  if (again)
  {
    // Waits for its transform as a new plan does (drainQueue draws it with the newest transform if
    // tf was cleared after the plan's own had come); drawn at once if tf has it.
    tf_waiting_ = true;
    tf_wait_since_ = std::chrono::steady_clock::now();
    tf_wait_error_ = "the plan received as ROS time jumped back waits for its transform";
    setStatus(rviz::StatusProperty::Warn, "Transform", QString(kWaitingForTfAfterJump) + tf_wait_error_);
    tf_filter_->add(again);
  }
}

void ProjectedPathDisplay::load(const rviz::Config& config)
{
  MFDClass::load(config);
  ConfigCheck check;
  for (rviz::FloatProperty* p : {spacing_property_, shaft_length_property_, shaft_diameter_property_,
                                 head_length_property_, head_diameter_property_, circle_diameter_property_,
                                 alpha_property_, height_property_, path_timeout_property_})
  {
    check.number(config.mapGetChild(p->getName()), p);
  }
  check.choice(config.mapGetChild(mode_property_->getName()), mode_property_, {"Exact", "Paper"}, "Exact");
  check.choice(config.mapGetChild(style_property_->getName()), style_property_, {"Flat", "3D"}, "Flat");
  QString report = check.report();
  for (const QString& part : {cue_properties_->checkLoaded(config), stop_properties_->checkLoaded(config),
                              corridor_properties_->checkLoaded(config), off_view_properties_->checkLoaded(config)})
  {
    if (!part.isEmpty())
    {
      report += (report.isEmpty() ? "" : "; ") + part;
    }
  }
  if (report.isEmpty())
  {
    deleteStatus("Config");
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, "Config", "Unusable values in the config replaced: " + report);
  }
}

SpacingParameters ProjectedPathDisplay::spacingParameters() const
{
  SpacingParameters p;
  p.mode = mode_property_->getOptionInt() == static_cast<int>(SpacingMode::Paper) ? SpacingMode::Paper
                                                                                  : SpacingMode::Exact;
  // As typed (0.3, not the float 0.300000012): marching takes the phase modulo the spacing of a
  // distance of ~1e8 m (speed x epoch time), where that float error would be metres.
  p.spacing = std::round(static_cast<double>(spacing_property_->getFloat()) * 1e6) / 1e6;
  p.arrow.shaft_length = shaft_length_property_->getFloat();
  p.arrow.shaft_diameter = shaft_diameter_property_->getFloat();
  p.arrow.head_length = head_length_property_->getFloat();
  p.arrow.head_diameter = head_diameter_property_->getFloat();
  p.circle_diameter = circle_diameter_property_->getFloat();
  p.speed_coding = stop_properties_->speedCoding(coded_speed_);
  return p;
}

void ProjectedPathDisplay::fixedFrameChanged()
{
  const nav_msgs::Path::ConstPtr last = last_msg_;
  MFDClass::fixedFrameChanged();  // retargets the tf filter and resets the display
  if (last)
  {
    // Through the tf filter again, stamped now: drawn as soon as the new fixed frame can be
    // reached (the old stamp may be older than tf's buffer, and would never pass).
    auto again = boost::make_shared<nav_msgs::Path>(*last);
    again->header.stamp = ros::Time::now();
    tf_filter_->add(again);
  }
}

void ProjectedPathDisplay::checkFrame(const ros::MessageEvent<nav_msgs::Path const>& event)
{
  const nav_msgs::Path::ConstPtr& msg = event.getConstMessage();
  after_jump_.received(msg);
  const boost::shared_ptr<ros::M_string>& header = event.getConnectionHeaderPtr();
  const auto latching = header ? header->find("latching") : ros::M_string::const_iterator();
  latched_publisher_ = header && latching != header->end() && latching->second == "1";
  if (msg->header.frame_id.empty())
  {
    setStatus(rviz::StatusProperty::Error, "Transform", "Path has an empty frame_id: nothing is drawn");
    return;
  }
  std::string error;
  if (context_->getFrameManager()->transformHasProblems(msg->header.frame_id, msg->header.stamp, error))
  {
    // Right after a backward jump of ROS time tf is empty until the bag plays it again: expected.
    // Otherwise the path waits in the tf filter: a warning, an error if it is still waiting after
    // kTfWaitGrace (drainQueue).
    const bool expected = RosClock::shared().policy().justStartedOrJumpedBack();
    tf_waiting_ = true;
    tf_wait_since_ = std::chrono::steady_clock::now();
    tf_wait_error_ = QString::fromStdString(error) + " (the path is drawn once the transform is available)";
    setStatus(rviz::StatusProperty::Warn, "Transform",
              QString(expected ? kWaitingForTfAfterJump : "Waiting for the transform (an error after 1 s): ") +
                  tf_wait_error_);
  }
}

void ProjectedPathDisplay::processMessage(const nav_msgs::Path::ConstPtr& msg)
{
  draw(msg, msg->header.stamp);
}

void ProjectedPathDisplay::draw(const nav_msgs::Path::ConstPtr& msg, const ros::Time& lookup_stamp)
{
  // The tf filter only lets a message through once its frame can be transformed; this lookup can
  // still fail if tf changed since, and then the previous drawing stays.
  Ogre::Vector3 position;
  Ogre::Quaternion orientation;
  if (!context_->getFrameManager()->getTransform(msg->header.frame_id, lookup_stamp, position, orientation))
  {
    std::string error;
    context_->getFrameManager()->transformHasProblems(msg->header.frame_id, msg->header.stamp, error);
    // Right after a backward jump of ROS time (a bag looping) rviz empties tf between the filter
    // letting the path through and this lookup: expected, a warning; the next path is drawn.
    const bool expected = RosClock::shared().policy().justStartedOrJumpedBack();
    setStatus(expected ? rviz::StatusProperty::Warn : rviz::StatusProperty::Error, "Transform",
              expected ? QString(kWaitingForTfAfterJump) + QString::fromStdString(error) : QString::fromStdString(error));
    return;
  }
  setStatus(rviz::StatusProperty::Ok, "Transform",
            lookup_stamp == msg->header.stamp ?
                "Transform OK" :
                "Transform OK (ROS time jumped back and tf was cleared after this plan's transform came: "
                "drawn with the newest transform)");
  tf_waiting_ = false;
  const RigidTransform to_fixed = RigidTransform::fromQuaternion(
      orientation.x, orientation.y, orientation.z, orientation.w, Vec3{position.x, position.y, position.z});
  dropped_poses_ = pathToFloorPoints(*msg, to_fixed, floor_points_);
  last_msg_ = msg;
  last_arrival_ = std::chrono::steady_clock::now();  // drained within milliseconds of its arrival
  rebuild();
}

void ProjectedPathDisplay::drainQueue()
{
  // A backward jump of ROS time (a bag loop): no cue state of before it is kept.
  if (epoch_.changed(RosClock::shared().tick()))
  {
    cue_source_.clear();
    stop_source_.forgetLaterThan(RosClock::shared().policy().rosNow());
    off_view_source_.resetCue();
  }
  drain();
  if (tf_waiting_ && after_jump_.last() &&
      PathAfterJump::olderThanTf(*context_->getFrameManager(), *after_jump_.last(), RosClock::shared().policy()))
  {
    draw(after_jump_.last(), ros::Time());  // its transform will never come: the newest one
  }
  if (tf_waiting_ && std::chrono::duration<double>(std::chrono::steady_clock::now() - tf_wait_since_).count() > kTfWaitGrace)
  {
    tf_waiting_ = false;  // reported once; a path that passes sets Transform OK
    setStatus(rviz::StatusProperty::Error, "Transform", tf_wait_error_);
  }
  const bool odometry = stop_source_.takeNews();
  const bool footprint = corridor_source_.takeNews();
  const bool lens = off_view_source_.takeNews();
  if ((cue_source_.takeNews() || odometry || footprint || lens) && arrow_mesh_ && isEnabled() && cuesActive())
  {
    drawCues(cueTime(), false);  // a new goal state shows at once, whatever the clock does
  }
  checkPathTimeout();
}

void ProjectedPathDisplay::checkPathTimeout()
{
  if (!last_msg_ || !arrow_mesh_)
  {
    return;  // nothing drawn
  }
  const double timeout = path_timeout_property_->getFloat();
  const double age = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_arrival_).count();
  if (!isStale(age, timeout))
  {
    return;
  }
  // Forget the path (a property change or a new fixed frame must not bring it back); only a new
  // path is drawn again. Raising the timeout afterwards shows nothing until then.
  last_msg_.reset();
  after_jump_.forget();
  floor_points_.clear();
  dropped_poses_ = 0;
  spaced_ = &empty_;
  arrow_mesh_->clear();
  circle_mesh_->clear();
  glyph_mesh_->clear();
  stop_mesh_->clear();
  corridor_mesh_->clear();
  off_view_mesh_->clear();
  off_view_drawn_.clear();
  deleteStatus("Style");
  setStatus(rviz::StatusProperty::Warn, "Path",
            QString("No new path for %1 s (Path timeout %2 s): arrows cleared").arg(age, 0, 'f', 1).arg(timeout));
  ProjectionChangeNotifier::notify();
  context_->queueRender();
}

void ProjectedPathDisplay::updateSpacing()
{
  spacer_.setParameters(spacingParameters());
  checkSpacingCombinations();
  rebuild();
}

void ProjectedPathDisplay::updateAppearance()
{
  redraw();
}

void ProjectedPathDisplay::checkGeometry(const SpacingParameters& p)
{
  if (p.mode == SpacingMode::Exact && p.spacing < p.arrow.length())
  {
    setStatus(rviz::StatusProperty::Warn, "Geometry",
              QString("Spacing %1 m is shorter than an arrow (shaft + head = %2 m): arrows overlap")
                  .arg(p.spacing, 0, 'g', 3)
                  .arg(p.arrow.length(), 0, 'g', 3));
  }
  else if (p.arrow.head_diameter < p.arrow.shaft_diameter)
  {
    setStatus(rviz::StatusProperty::Warn, "Geometry",
              QString("Head diameter %1 m is narrower than the shaft (%2 m): arrows lose their heads")
                  .arg(p.arrow.head_diameter, 0, 'g', 3)
                  .arg(p.arrow.shaft_diameter, 0, 'g', 3));
  }
  else
  {
    deleteStatus("Geometry");
  }
}

void ProjectedPathDisplay::rebuild()
{
  checkGeometry(spacer_.parameters());
  if (!last_msg_)
  {
    return;  // no path (in the fixed frame) yet
  }
  spaced_ = &spacer_.space(floor_points_);
  spaced_phase_ = 0.0;
  redraw();
  // Counted from the triangles: an invalid (degenerate) arrow is not drawn, so not counted.
  const std::size_t drawn = cuesActive() ? cue_drawn_.arrowsDrawn() : triangles_.arrowsDrawn();
  const std::size_t dropped = dropped_poses_ + spaced_->dropped_points;
  if (!spaced_->has_destination)
  {
    setStatus(rviz::StatusProperty::Warn, "Path",
              dropped > 0 ? QString("All %1 poses have NaN/Inf or out-of-range values: nothing to draw").arg(dropped)
                          : QString("Empty path (no poses): nothing to draw"));
  }
  else if (dropped > 0)
  {
    setStatus(rviz::StatusProperty::Warn, "Path",
              QString("%1 poses with NaN/Inf or out-of-range values dropped; %2 arrows drawn").arg(dropped).arg(drawn));
  }
  else if (spaced_->truncated)
  {
    setStatus(rviz::StatusProperty::Warn, "Path",
              QString("Path too long for the spacing: only the %1 arrows nearest the destination are drawn")
                  .arg(drawn));
  }
  else
  {
    setStatus(rviz::StatusProperty::Ok, "Path",
              QString("%1 arrows on %2 m of path").arg(drawn).arg(spaced_->path_length, 0, 'f', 2));
  }
}

void ProjectedPathDisplay::redraw()
{
  if (!arrow_mesh_)
  {
    return;
  }
  if (cuesActive())
  {
    if (style_property_->getOptionInt() == kSolid)
    {
      setStatus(rviz::StatusProperty::Warn, "Style", "A cue is on: arrows are drawn Flat (3D is not used with cues)");
    }
    else
    {
      deleteStatus("Style");
    }
    drawCues(cueTime(), true);
    return;
  }
  glyph_mesh_->clear();
  stop_mesh_->clear();
  corridor_mesh_->clear();
  off_view_mesh_->clear();
  off_view_drawn_.clear();
  const double height = height_property_->getFloat();
  const float alpha = alpha_property_->getFloat();
  Ogre::ColourValue arrow_colour = arrow_color_property_->getOgreColor();
  Ogre::ColourValue circle_colour = circle_color_property_->getOgreColor();
  arrow_colour.a = alpha;
  circle_colour.a = alpha;
  const bool solid = style_property_->getOptionInt() == kSolid;
  triangles_.build(*spaced_, spacer_.parameters(),
                   solid ? PathTriangles::ArrowStyle::Solid : PathTriangles::ArrowStyle::Flat);
  if (triangles_.arrowsLeftOut() > 0)
  {
    setStatus(rviz::StatusProperty::Warn, "Style",
              QString("3D draws at most %1 arrows (those nearest the destination): %2 left out; Flat draws them all")
                  .arg(PathTriangles::kMaxSolidArrows)
                  .arg(triangles_.arrowsLeftOut()));
  }
  else
  {
    deleteStatus("Style");
  }
  if (solid)
  {
    arrow_mesh_->setSolidTriangles(triangles_.solidArrows(), height + kArrowLift, arrow_colour);
  }
  else
  {
    arrow_mesh_->setFlatTriangles(triangles_.flatArrows(), height + kArrowLift, arrow_colour);
  }
  circle_mesh_->setFlatTriangles(triangles_.destination(), height, circle_colour);
  ++mesh_builds_;
  ProjectionChangeNotifier::notify();
  context_->queueRender();
}

std::size_t ProjectedPathDisplay::arrowTriangleCount() const
{
  return arrow_mesh_ ? arrow_mesh_->triangleCount() : 0;
}

std::size_t ProjectedPathDisplay::circleTriangleCount() const
{
  return circle_mesh_ ? circle_mesh_->triangleCount() : 0;
}
}  // namespace rviz_projector

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(rviz_projector::ProjectedPathDisplay, rviz::Display)
