#include "rviz_projector/displays/projection_mask_display.h"

#include <algorithm>
#include <cmath>

#include <OgreRenderSystem.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <OgreViewport.h>
#include <rviz/config.h>
#include <rviz/display_context.h>
#include <rviz/frame_manager.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/status_property.h>
#include <rviz/properties/tf_frame_property.h>
#include <rviz/render_panel.h>
#include <rviz/view_manager.h>

#include "rviz_projector/displays/acknowledge_properties.h"
#include "rviz_projector/displays/config_check.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/displays/projection_change_notifier.h"
#include "rviz_projector/displays/ros_clock.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
/// Cloud points this close to z = 0 are the floor itself, not something standing on it.
constexpr double kFloorClearance = 0.03;
/// A dense cloud is masked by cells (core snapToCells), at most this many: a 640x480 depth image
/// would otherwise be 300,000 columns (9 million vertices) a frame.
constexpr std::size_t kMaxCloudColumns = 20000;
/// A scan with more returns than this is masked by cells like a cloud (same cell, same cap): a
/// 200,000-return scan would otherwise be 200,000 columns (6 million vertices) a frame. Real
/// 2D scanners give at most a few thousand returns, masked return by return.
constexpr std::size_t kMaxScanColumns = 20000;
/// The Acknowledge arcs' height above the floor: over the path's arrows (1 cm by default).
constexpr double kAcknowledgeHeight = 0.015;
/// Seconds between two redraws of a fading arc.
constexpr double kFadeStep = 1.0 / 60.0;

/// The cloud's cell side: Margin (so a column widens by at most half a margin), at least 5 cm.
double cloudCell(double margin)
{
  return std::max(margin, 0.05);
}

RigidTransform fromOgre(const Ogre::Vector3& p, const Ogre::Quaternion& q)
{
  return RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, Vec3{p.x, p.y, p.z});
}
}  // namespace

ProjectionMaskDisplay::ProjectionMaskDisplay()
{
  height_property_ = new rviz::FloatProperty(
      "Height", 2.0f,
      "Metres: each return becomes a black column from the floor up to this height in the projector's view.", this,
      SLOT(updateShape()), this);
  height_property_->setMin(0.0f);
  height_property_->setMax(100.0f);
  margin_property_ = new rviz::FloatProperty(
      "Margin", 0.1f,
      "Metres: half-width of each column around its return (widens the mask beyond what the scanner saw).", this,
      SLOT(updateShape()), this);
  margin_property_->setMin(0.0f);
  margin_property_->setMax(10.0f);
  max_age_property_ = new rviz::FloatProperty(
      "Max scan age", 0.5f,
      "Seconds (ROS time, from the message stamp): older scans are dropped, and the mask is released when no fresh "
      "one arrives for this long. A stale mask would shade where a person was, not where they are.",
      this);
  max_age_property_->setMin(0.0f);
  main_view_property_ = new rviz::BoolProperty(
      "Show in main view", false,
      "Draw the columns translucent in rviz's main view, for setting up. The projector views always get them "
      "black and opaque; without this the main view shows nothing of the mask.",
      this, SLOT(updateOutline()), this);
  cloud_topic_property_ = new rviz::RosTopicProperty(
      "Point cloud topic", "", QString::fromStdString(ros::message_traits::datatype<sensor_msgs::PointCloud2>()),
      "Optional sensor_msgs/PointCloud2 (e.g. a depth camera): its points between the floor and Height mask too. "
      "Empty: none.",
      this, SLOT(updateCloudTopic()), this);
  ack_properties_ = std::make_unique<AcknowledgeProperties>(this);
}

ProjectionMaskDisplay::~ProjectionMaskDisplay()
{
  pauseDraining();
  cloud_sub_.shutdown();
  if (main_window_)
  {
    // The main view's window may be gone already (rviz closing): only a window OGRE still has.
    Ogre::RenderSystem* system = Ogre::Root::getSingletonPtr() ? Ogre::Root::getSingleton().getRenderSystem() : nullptr;
    if (system && system->getRenderTarget(main_window_name_) == main_window_)
    {
      main_window_->removeListener(this);
    }
  }
  ack_.unsubscribe();
  occluder_mesh_.reset();
  outline_mesh_.reset();
  ack_mesh_.reset();
  // OGRE destroys no child with its parent: rviz destroys the display's scene node, which only
  // detaches this one, left in the scene manager for ever (issue 23: one leaked per display).
  if (occluder_node_)
  {
    scene_manager_->destroySceneNode(occluder_node_);
  }
  if (ack_node_)
  {
    scene_manager_->destroySceneNode(ack_node_);
  }
  if (outline_node_)
  {
    scene_manager_->destroySceneNode(outline_node_);  // not under the display's node: ours to destroy
  }
}

void ProjectionMaskDisplay::onInitialize()
{
  attach(update_nh_);
  MFDClass::onInitialize();
  occluder_node_ = scene_node_->createChildSceneNode();
  occluder_mesh_ = std::make_unique<FloorMesh>(scene_manager_, occluder_node_);
  // The arcs under the display's node: the projectors' Visibility ticks apply; shown in the main view.
  ack_node_ = scene_node_->createChildSceneNode();
  ack_mesh_ = std::make_unique<FloorMesh>(scene_manager_, ack_node_);
  ack_properties_->robot_frame->setFrameManager(context_->getFrameManager());
  // The outline is not under the display's node: rviz sets the visibility flags of everything there
  // (the Visibility ticks of each projector). Its own flag, the main view's bit only, keeps it out of
  // every projector view (their viewports show only their own bit).
  outline_node_ = scene_manager_->getRootSceneNode()->createChildSceneNode();
  outline_mesh_ = std::make_unique<FloorMesh>(scene_manager_, outline_node_);
  outline_mesh_->setVisibilityFlags(context_->getDefaultVisibilityBit());
  outline_mesh_->setLayer(10);  // translucent, over every floor layer of ProjectedPath (1..6)
  updateOutline();
  rviz::ViewManager* views = context_->getViewManager();
  rviz::RenderPanel* panel = views ? views->getRenderPanel() : nullptr;
  main_window_ = panel ? panel->getRenderWindow() : nullptr;
  if (main_window_)
  {
    main_window_name_ = main_window_->getName();
    main_window_->addListener(this);
  }
  // Drained while enabled (onEnable starts the timer, onDisable stops it).
  setDrainHandler([this] { drainQueue(); });
  setStatus(rviz::StatusProperty::Warn, "Scan", "No scan received yet: nothing is masked");
}

void ProjectionMaskDisplay::onEnable()
{
  MFDClass::onEnable();
  resumeDraining();
  scene_node_->setVisible(true);
  occluder_mesh_->setShown(true);
  updateOutline();
  updateCloudTopic();
  updateAcknowledge();
  ProjectionChangeNotifier::notify();
}

void ProjectionMaskDisplay::onDisable()
{
  MFDClass::onDisable();
  pauseDraining();  // nothing to drain: no subscription while disabled
  cloud_sub_.shutdown();
  ack_.unsubscribe();
  scene_node_->setVisible(false);
  occluder_mesh_->setShown(false);
  updateOutline();
  clearMask();
  ProjectionChangeNotifier::notify();
}

void ProjectionMaskDisplay::reset()
{
  MFDClass::reset();
  clearMask();
  setStatus(rviz::StatusProperty::Warn, "Scan", "No scan received yet: nothing is masked");
}

void ProjectionMaskDisplay::load(const rviz::Config& config)
{
  MFDClass::load(config);
  ConfigCheck check;
  for (rviz::FloatProperty* p : {height_property_, margin_property_, max_age_property_})
  {
    check.number(config.mapGetChild(p->getName()), p);
  }
  const QString acknowledge = ack_properties_->checkLoaded(config);
  if (check.report().isEmpty() && acknowledge.isEmpty())
  {
    deleteStatus("Config");
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, "Config", "Unusable values in the config replaced: " +
                                                   QStringList({check.report(), acknowledge}).filter(QRegExp(".")).join("; "));
  }
}

void ProjectionMaskDisplay::preViewportUpdate(const Ogre::RenderTargetViewportEvent& /*event*/)
{
  if (!occluder_node_)
  {
    return;
  }
  occluder_mesh_->setShown(false);
}

void ProjectionMaskDisplay::postViewportUpdate(const Ogre::RenderTargetViewportEvent& /*event*/)
{
  if (!occluder_node_)
  {
    return;
  }
  occluder_mesh_->setShown(isEnabled());
}

void ProjectionMaskDisplay::updateOutline()
{
  if (outline_mesh_)
  {
    outline_mesh_->setShown(isEnabled() && main_view_property_->getBool());
    context_->queueRender();
  }
}

bool ProjectionMaskDisplay::unusableStamp(const ros::Time& stamp, const char* status, const char* what)
{
  if (stamp.isZero())
  {
    setStatus(rviz::StatusProperty::Warn, status,
              QString("%1 has no stamp (0): its age cannot be checked, dropped (a stale mask is worse than none)")
                  .arg(what));
    return true;
  }
  const double max_age = max_age_property_->getFloat();
  // A data age: ROS time, as read by drainQueue before it handled this message (never a new reading
  // here: a jump seen in the middle of a drain would clear this very scan at the next one).
  const double age = RosClock::shared().policy().rosNow() - stamp.toSec();
  if (max_age > 0.0 && age > max_age)
  {
    setStatus(rviz::StatusProperty::Warn, status,
              QString("%1 %2 s old (Max scan age %3 s): dropped; is the sensor's clock in step with this one?")
                  .arg(what)
                  .arg(age, 0, 'f', 2)
                  .arg(max_age));
    return true;
  }
  return false;
}

void ProjectionMaskDisplay::processMessage(const sensor_msgs::LaserScan::ConstPtr& msg)
{
  if (unusableStamp(msg->header.stamp, "Scan", "Scan"))
  {
    return;
  }
  Ogre::Vector3 position;
  Ogre::Quaternion orientation;
  if (!context_->getFrameManager()->getTransform(msg->header, position, orientation))
  {
    // Right after a backward jump of ROS time tf is empty until the bag plays it again: expected.
    const bool expected = RosClock::shared().policy().justStartedOrJumpedBack();
    setStatus(expected ? rviz::StatusProperty::Warn : rviz::StatusProperty::Error, "Transform",
              QString("%1No transform from '%2' at the scan's stamp")
                  .arg(expected ? kWaitingForTfAfterJump : "")
                  .arg(QString::fromStdString(msg->header.frame_id)));
    return;
  }
  setStatus(rviz::StatusProperty::Ok, "Transform", "Transform OK");
  ScanView scan;
  scan.angle_min = msg->angle_min;
  scan.angle_increment = msg->angle_increment;
  scan.range_min = msg->range_min;
  scan.range_max = msg->range_max;
  scan.ranges = msg->ranges.data();
  scan.count = msg->ranges.size();
  const MaskInputCount count = scanToFloorPoints(scan, fromOgre(position, orientation), scan_points_);
  scan_stamp_ = msg->header.stamp;
  if (ack_properties_->enabled->getBool())
  {
    // The returns in the scan's order (before any thinning to cells): people are their clusters.
    ack_.addScan(scan_points_, scan_stamp_.toSec(), ack_properties_->clusters(), ack_properties_->tracker());
  }
  scan_in_cells_ = scan_points_.size() > kMaxScanColumns;
  if (scan_in_cells_)
  {
    const double cell = cloudCell(margin_property_->getFloat());
    const bool complete = snapToCells(scan_points_, cell, kMaxCloudColumns);
    setStatus(complete ? rviz::StatusProperty::Ok : rviz::StatusProperty::Warn, "Scan",
              QString("%1 returns (more than %2): masked by %3 cells of %4 m%5; %6 ignored")
                  .arg(count.used)
                  .arg(kMaxScanColumns)
                  .arg(scan_points_.size())
                  .arg(cell)
                  .arg(complete ? QString() : QString(", only the first %1 cells").arg(kMaxCloudColumns))
                  .arg(count.ignored));
  }
  else if (count.ignored > 0)
  {
    setStatus(rviz::StatusProperty::Ok, "Scan",
              QString("%1 returns masked; %2 ignored (NaN/Inf, out of range or no return)").arg(count.used).arg(count.ignored));
  }
  else
  {
    setStatus(rviz::StatusProperty::Ok, "Scan", QString("%1 returns masked").arg(count.used));
  }
  rebuild();
}

void ProjectionMaskDisplay::onCloud(const sensor_msgs::PointCloud2::ConstPtr& msg)
{
  pending_cloud_ = msg;  // a newer cloud replaces one still waiting for its transform
  tryPendingCloud();
}

void ProjectionMaskDisplay::tryPendingCloud()
{
  if (!pending_cloud_)
  {
    return;
  }
  const sensor_msgs::PointCloud2& msg = *pending_cloud_;
  if (unusableStamp(msg.header.stamp, "Point cloud", "Point cloud"))
  {
    pending_cloud_.reset();
    return;
  }
  Ogre::Vector3 position;
  Ogre::Quaternion orientation;
  if (!context_->getFrameManager()->getTransform(msg.header, position, orientation))
  {
    // Kept and retried at every drain: tf often arrives after the cloud.
    setStatus(rviz::StatusProperty::Warn, "Point cloud",
              QString("Waiting for the transform from '%1' at the cloud's stamp (dropped after Max scan age)")
                  .arg(QString::fromStdString(msg.header.frame_id)));
    return;
  }
  const std::string problem = readCloudXyz(msg, cloud_scratch_);
  const ros::Time stamp = msg.header.stamp;
  pending_cloud_.reset();
  if (!problem.empty())
  {
    setStatus(rviz::StatusProperty::Error, "Point cloud",
              QString("Unusable cloud (%1): dropped").arg(QString::fromStdString(problem)));
    return;
  }
  const RigidTransform to_fixed = fromOgre(position, orientation);
  for (Vec3& point : cloud_scratch_)
  {
    point = to_fixed.apply(point);  // in place: no second copy of a 300,000-point cloud
  }
  cloud_fixed_.swap(cloud_scratch_);  // both buffers keep their capacity for the next cloud
  cloud_stamp_ = stamp;
  updateCloudPoints();
  rebuild();
}

void ProjectionMaskDisplay::updateCloudPoints()
{
  cloud_points_.clear();
  if (cloud_stamp_.isZero())
  {
    return;
  }
  const MaskInputCount count =
      cloudToFloorPoints(cloud_fixed_, kFloorClearance, height_property_->getFloat(), cloud_points_);
  const bool complete = snapToCells(cloud_points_, cloudCell(margin_property_->getFloat()), kMaxCloudColumns);
  if (!complete)
  {
    setStatus(rviz::StatusProperty::Warn, "Point cloud",
              QString("%1 points in more than %2 cells of %3 m: only the first %2 cells are masked")
                  .arg(count.used)
                  .arg(kMaxCloudColumns)
                  .arg(cloudCell(margin_property_->getFloat())));
    return;
  }
  setStatus(rviz::StatusProperty::Ok, "Point cloud",
            QString("%1 points masked (%2 columns of %3 m cells); %4 on the floor, above Height or NaN")
                .arg(count.used)
                .arg(cloud_points_.size())
                .arg(cloudCell(margin_property_->getFloat()))
                .arg(count.ignored));
}

void ProjectionMaskDisplay::drainQueue()
{
  // A backward jump of ROS time (a bag loop): no scan or cloud of before it is kept.
  if (epoch_.changed(RosClock::shared().tick()))
  {
    clearMask();
    ProjectionChangeNotifier::notify();
  }
  drain();
  tryPendingCloud();
  releaseStale();
  // A new path; or an arc fading (once its person left the scan), redrawn at most every
  // kFadeStep of ROS time (the drain runs every 5 ms, projectors show at most 60 frames/s).
  const bool news = ack_.takeNews();
  const double now = RosClock::shared().policy().rosNow();
  if (news || (ack_.fading() && !(std::abs(now - ack_faded_at_) < kFadeStep)))
  {
    ack_faded_at_ = now;
    redrawAcknowledge();
  }
}

void ProjectionMaskDisplay::releaseStale()
{
  const double max_age = max_age_property_->getFloat();
  if (!(max_age > 0.0))
  {
    return;
  }
  const ros::Time now(std::max(0.0, RosClock::shared().policy().rosNow()));  // read by drainQueue
  bool changed = false;
  if (!scan_stamp_.isZero() && (now - scan_stamp_).toSec() > max_age)
  {
    scan_stamp_ = ros::Time();
    scan_points_.clear();
    ack_.scanLost(now.toSec(), ack_properties_->tracker());
    setStatus(rviz::StatusProperty::Warn, "Scan",
              QString("No scan newer than Max scan age (%1 s): mask released, nothing is masked").arg(max_age));
    changed = true;
  }
  if (!cloud_stamp_.isZero() && (now - cloud_stamp_).toSec() > max_age)
  {
    cloud_stamp_ = ros::Time();
    cloud_points_.clear();
    setStatus(rviz::StatusProperty::Warn, "Point cloud",
              QString("No cloud newer than Max scan age (%1 s): its part of the mask released").arg(max_age));
    changed = true;
  }
  if (changed)
  {
    rebuild();
  }
}

void ProjectionMaskDisplay::updateShape()
{
  updateCloudPoints();  // Height filters the cloud's points, Margin sets its cells
  rebuild();
}

void ProjectionMaskDisplay::updateCloudTopic()
{
  cloud_sub_.shutdown();
  cloud_points_.clear();
  cloud_stamp_ = ros::Time();
  pending_cloud_.reset();
  deleteStatus("Point cloud");
  const std::string topic = cloud_topic_property_->getStdString();
  if (!initialized() || !isEnabled() || topic.empty())
  {
    rebuild();
    return;
  }
  try
  {
    cloud_sub_ = update_nh_.subscribe(topic, 2, &ProjectionMaskDisplay::onCloud, this);
    setStatus(rviz::StatusProperty::Warn, "Point cloud", "No cloud received yet");
  }
  catch (const ros::Exception& e)
  {
    setStatus(rviz::StatusProperty::Error, "Point cloud", QString("Cannot subscribe: %1").arg(e.what()));
  }
  rebuild();
}

void ProjectionMaskDisplay::clearMask()
{
  scan_points_.clear();
  scan_in_cells_ = false;
  cloud_points_.clear();
  scan_stamp_ = ros::Time();
  cloud_stamp_ = ros::Time();
  pending_cloud_.reset();
  ack_.clear();
  rebuild();
}

void ProjectionMaskDisplay::rebuild()
{
  if (!occluder_mesh_)
  {
    return;
  }
  const double height = height_property_->getFloat();
  const double margin = margin_property_->getFloat();
  // A scan thinned to cells (more than kMaxScanColumns returns) widens by half a cell, as a cloud.
  const double scan_margin = scan_in_cells_ ? margin + 0.5 * cloudCell(margin) : margin;
  // Cloud points stand for their cells: the wider margin covers every point of the cell.
  const double cloud_margin = margin + 0.5 * cloudCell(margin);
  // The columns' union drawn once (the same solid without the overlapping columns' overdraw); the
  // columns themselves when the union is not formed (core occluder_union.h).
  merged_ = union_.build({{&scan_points_, scan_margin}, {&cloud_points_, cloud_margin}}, height);
  if (!merged_)
  {
    occluders_.build(scan_points_, height, scan_margin);
    occluders_.append(cloud_points_, height, cloud_margin);
  }
  const std::vector<MeshVertex>& solid = merged_ ? union_.triangles() : occluders_.triangles();
  if (!(height > 0.0 && margin > 0.0))
  {
    setStatus(rviz::StatusProperty::Warn, "Shape",
              QString("%1 is 0: nothing is masked").arg(height > 0.0 ? "Margin" : "Height"));
  }
  else
  {
    deleteStatus("Shape");
  }
  occluder_mesh_->setSolidTriangles(solid, 0.0, Ogre::ColourValue::Black);
  outline_mesh_->setSolidTriangles(solid, 0.0, Ogre::ColourValue(1.0f, 0.6f, 0.0f, 0.35f));
  redrawAcknowledge();  // in the same frame as the scan's mask
  ProjectionChangeNotifier::notify();
  context_->queueRender();
}

void ProjectionMaskDisplay::updateAcknowledge()
{
  if (!initialized())
  {
    return;
  }
  if (isEnabled() && ack_properties_->enabled->getBool())
  {
    ack_.subscribe(update_nh_, ack_properties_->wantedTopic());
  }
  else
  {
    ack_.unsubscribe();
  }
  redrawAcknowledge();
}

std::size_t ProjectionMaskDisplay::acknowledgeTriangles() const
{
  return ack_mesh_ ? ack_mesh_->triangleCount() : 0;
}

void ProjectionMaskDisplay::redrawAcknowledge()
{
  if (!ack_mesh_)
  {
    return;
  }
  const AcknowledgeProperties& props = *ack_properties_;
  if (!isEnabled() || !props.enabled->getBool())
  {
    deleteStatus("Acknowledge");
    ack_status_.clear();
    if (ack_drawn_)
    {
      ack_mesh_->clear();
      ack_drawn_ = false;
      ProjectionChangeNotifier::notify();
    }
    return;
  }
  const double now = RosClock::shared().policy().rosNow();
  // The square columns reach Margin x sqrt(2) from a return (a scan thinned to cells: its wider margin).
  const double margin = margin_property_->getFloat();
  const double column = scan_in_cells_ ? margin + cloudCell(margin) : margin;
  const AcknowledgeFrame& frame = ack_.build(now, *context_->getFrameManager(), props.robot_frame->getFrameStd(),
                                             props.arc(), props.tracker(), column * std::sqrt(2.0));
  const QColor c = props.color->getColor();
  if (ack_drawn_ || !frame.triangles.empty())
  {
    ack_mesh_->setFlatTriangles(frame.triangles, frame.alpha, kAcknowledgeHeight,
                                Ogre::ColourValue(c.redF(), c.greenF(), c.blueF(), 1.0f));
    ack_drawn_ = !frame.triangles.empty();
    ProjectionChangeNotifier::notify();
    context_->queueRender();
  }
  const QString text = QString::fromStdString(frame.status.text);
  if (text != ack_status_)
  {
    ack_status_ = text;
    setStatus(frame.status.level == CueStatus::Level::Ok
                  ? rviz::StatusProperty::Ok
                  : (frame.status.level == CueStatus::Level::Warn ? rviz::StatusProperty::Warn : rviz::StatusProperty::Error),
              "Acknowledge", text);
  }
}
}  // namespace rviz_projector

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(rviz_projector::ProjectionMaskDisplay, rviz::Display)
