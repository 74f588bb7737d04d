// rviz display "rviz_projector/ProjectionMask" (issue 15): black occluders over everything a laser
// scanner (and optionally a point cloud) sees above the floor, drawn only in projector views, so no
// light falls on people, legs or bags and arrows behind them are cut where they block the beam.
// An orchestrator: the core's scanToFloorPoints / OccluderMesh make the geometry, FloorMesh draws it,
// MainViewExclusion keeps it out of rviz's main view. The Acknowledge group (AcknowledgeProperties,
// AcknowledgeSource) draws an arc in front of each person near the path ahead, from the same scan.
#pragma once

#include "rviz_projector/core/clock_policy.h"

#ifndef Q_MOC_RUN
#include <memory>
#include <string>
#include <vector>

#include <OgreRenderTargetListener.h>
#include <QTimer>
#include <ros/subscriber.h>
#include <rviz/message_filter_display.h>
#include <sensor_msgs/LaserScan.h>
#include <sensor_msgs/PointCloud2.h>

#include "rviz_projector/core/occluder_union.h"
#include "rviz_projector/core/projection_mask.h"
#include "rviz_projector/core/vec2.h"
#include "rviz_projector/displays/acknowledge_source.h"
#include "rviz_projector/displays/private_callback_queue.h"
#endif

namespace Ogre
{
class RenderWindow;
class SceneNode;
}  // namespace Ogre

namespace rviz
{
class BoolProperty;
class FloatProperty;
class RosTopicProperty;
}  // namespace rviz

namespace rviz_projector
{
class FloorMesh;
struct AcknowledgeProperties;

class ProjectionMaskBase : protected PrivateCallbackQueue, public rviz::MessageFilterDisplay<sensor_msgs::LaserScan>
{
};

class ProjectionMaskDisplay : public ProjectionMaskBase, public Ogre::RenderTargetListener
{
  Q_OBJECT
public:
  ProjectionMaskDisplay();
  ~ProjectionMaskDisplay() override;

  void reset() override;
  void load(const rviz::Config& config) override;

  /// Occluder columns drawn now (one per used return or cloud point).
  std::size_t columns() const { return merged_ ? union_.squares() : occluders_.columns(); }
  /// The Acknowledge part (tests read its tracks) and the arcs' triangles drawn now.
  const AcknowledgeSource& acknowledgeSource() const { return ack_; }
  std::size_t acknowledgeTriangles() const;

  // The main view's render window: the occluders are hidden while it renders, the outline shown.
  void preViewportUpdate(const Ogre::RenderTargetViewportEvent& event) override;
  void postViewportUpdate(const Ogre::RenderTargetViewportEvent& event) override;

protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;
  void processMessage(const sensor_msgs::LaserScan::ConstPtr& msg) override;

private Q_SLOTS:
  void drainQueue();
  void updateShape();
  void updateCloudTopic();
  void updateOutline();
  void updateAcknowledge();

private:
  void onCloud(const sensor_msgs::PointCloud2::ConstPtr& msg);
  /// Uses the pending cloud once tf has its transform at the cloud's stamp (a small tf filter:
  /// retried at every drain until the cloud is older than Max scan age).
  void tryPendingCloud();
  /// The stored cloud's points between the floor and Height, thinned to cells (cloud_points_).
  void updateCloudPoints();
  /// Unusable by its stamp: zero (age unknown) or older than Max scan age (ROS time). True, with a
  /// status, when the message must be dropped.
  bool unusableStamp(const ros::Time& stamp, const char* status, const char* what);
  /// Drops scan and cloud once older than Max scan age (a stale mask is worse than none).
  void releaseStale();
  void rebuild();
  void clearMask();
  /// The Acknowledge arcs at this instant: built by ack_, drawn by ack_mesh_, with the status.
  void redrawAcknowledge();

  rviz::FloatProperty* height_property_;
  rviz::FloatProperty* margin_property_;
  rviz::FloatProperty* max_age_property_;
  rviz::BoolProperty* main_view_property_;
  rviz::RosTopicProperty* cloud_topic_property_;

  EpochWatch epoch_;  ///< of RosClock::shared(): a backward jump of ROS time forgets the old state
  ros::Subscriber cloud_sub_;
  std::vector<Vec2> scan_points_;
  bool scan_in_cells_ = false;  ///< scan_points_ are cell centres (a scan of more than kMaxScanColumns)
  std::vector<Vec2> cloud_points_;
  std::vector<Vec3> cloud_scratch_;   // the cloud being read (its own frame, then the fixed frame)
  std::vector<Vec3> cloud_fixed_;     // the last cloud used, in the fixed frame (Height may change)
  sensor_msgs::PointCloud2::ConstPtr pending_cloud_;
  ros::Time scan_stamp_;   // zero: no scan in the mask
  ros::Time cloud_stamp_;  // zero: no cloud in the mask
  OccluderMesh occluders_;
  OccluderUnion union_;  ///< what is drawn, unless it could not be formed (then occluders_)
  bool merged_ = false;   ///< whether union_ is what is drawn
  Ogre::SceneNode* occluder_node_ = nullptr;
  Ogre::SceneNode* outline_node_ = nullptr;
  std::unique_ptr<FloorMesh> occluder_mesh_;
  std::unique_ptr<FloorMesh> outline_mesh_;
  Ogre::RenderWindow* main_window_ = nullptr;
  std::string main_window_name_;  ///< kept: the window may be gone before this display (never ask it then)
  std::unique_ptr<AcknowledgeProperties> ack_properties_;
  AcknowledgeSource ack_;
  Ogre::SceneNode* ack_node_ = nullptr;
  std::unique_ptr<FloorMesh> ack_mesh_;
  QString ack_status_;  ///< the status shown (set again only when it changes)
  bool ack_drawn_ = false;
  double ack_faded_at_ = 0.0;  ///< ROS time of the last redraw of a fading arc
};
}  // namespace rviz_projector
