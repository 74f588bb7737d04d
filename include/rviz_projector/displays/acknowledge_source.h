// The Acknowledge cue of ProjectionMaskDisplay (issue 25, part 4), one part of it: the path topic
// (on the display's private callback queue), the people of each scan (core findPersonClusters) and
// who is who between scans (core PersonTracker), and at a given instant the arcs' triangles (core
// acknowledgeArc, one per person near the path ahead) with each vertex's opacity (the fade) and
// what the "Acknowledge" status says. The display draws the triangles; this part draws nothing.
#pragma once

#ifndef Q_MOC_RUN
#include <cstddef>
#include <string>
#include <vector>

#include <nav_msgs/Path.h>
#include <ros/node_handle.h>

#include "rviz_projector/core/acknowledge_arc.h"
#include "rviz_projector/core/person_clusters.h"
#include "rviz_projector/core/person_tracker.h"
#include "rviz_projector/displays/news_flag.h"
#include "rviz_projector/displays/path_cue_source.h"
#include "rviz_projector/displays/topic_subscription.h"
#endif

namespace rviz
{
class FrameManager;
}  // namespace rviz

namespace rviz_projector
{
/// The arcs to draw now.
struct AcknowledgeFrame
{
  std::vector<Vec2> triangles;
  std::vector<float> alpha;      ///< one per vertex of `triangles`: the person's fade
  std::size_t acknowledged = 0;  ///< people with an arc
  CueStatus status;
};

class AcknowledgeSource
{
public:
  /// Clusters beyond this many in one scan are not tracked (a 100,000-return scan of noise would
  /// otherwise make tens of thousands of "people"); the status says so.
  static constexpr std::size_t kMaxPeople = 64;

  /// Subscribes to the path `topic` with `nh`; empty: none. The same topic again changes nothing.
  void subscribe(ros::NodeHandle& nh, const std::string& topic);
  void unsubscribe();
  /// Forgets the people and the path (rviz's Reset, a backward jump of ROS time, switched off).
  void clear();

  /// The floor points (fixed frame, in the scan's order) of a scan stamped `stamp` (seconds):
  /// its people are found and associated with the tracks.
  void addScan(const std::vector<Vec2>& points, double stamp, const ClusterLimits& limits,
               const TrackerParameters& tracker);
  /// No scan any more (released as stale): everyone starts fading from when they were last seen.
  void scanLost(double now, const TrackerParameters& tracker);
  /// Drops the tracks faded out at `now`; true when some were.
  bool expire(double now, const TrackerParameters& tracker) { return tracker_.expire(now, tracker); }

  /// The arcs at `now` (ROS time, seconds): robot and path looked up with `frames` (latest tf, in
  /// its fixed frame). `feet_margin` is added to each cluster's radius (the mask's column corner).
  const AcknowledgeFrame& build(double now, rviz::FrameManager& frames, const std::string& robot_frame,
                                const AcknowledgeParameters& arc, const TrackerParameters& tracker,
                                double feet_margin);

  /// Whether any person's arc is fading (the picture changes with time).
  bool fading() const { return tracker_.fading(); }
  const std::vector<PersonTrack>& tracks() const { return tracker_.tracks(); }
  /// Path messages taken so far (tests wait for theirs).
  std::size_t pathMessages() const { return path_messages_; }
  /// Whether a path arrived since the last call.
  bool takeNews() { return news_.take(); }

private:
  void onPath(const nav_msgs::Path::ConstPtr& msg);
  /// The path's points in the fixed frame (path_points_); false with a status when unusable.
  bool pathPoints(rviz::FrameManager& frames, CueStatus& status);

  TopicSubscription subscription_;
  nav_msgs::Path::ConstPtr path_;
  std::vector<Vec2> path_points_;
  std::vector<PersonCluster> clusters_;
  PersonTracker tracker_;
  AcknowledgeFrame frame_;
  bool scan_seen_ = false;
  std::size_t clusters_found_ = 0;   // person-sized clusters of the last scan (before kMaxPeople)
  NewsFlag news_;
  std::size_t path_messages_ = 0;
};
}  // namespace rviz_projector
