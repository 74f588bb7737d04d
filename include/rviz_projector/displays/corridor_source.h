// Where the corridor's footprint comes from: the Radius, the Polygon typed in the properties, or a
// geometry_msgs/PolygonStamped topic (on the display's private callback queue) moved into the Robot
// frame with tf. One part of ProjectedPathDisplay: it returns the footprint and what the "Corridor"
// status says.
#pragma once

#ifndef Q_MOC_RUN
#include <string>
#include <vector>

#include <geometry_msgs/PolygonStamped.h>
#include <ros/node_handle.h>
#include <ros/subscriber.h>

#include "rviz_projector/core/vec2.h"
#include "rviz_projector/displays/news_flag.h"
#include "rviz_projector/displays/path_cue_source.h"
#include "rviz_projector/displays/topic_subscription.h"
#endif

namespace tf2_ros
{
class Buffer;
}

namespace rviz_projector
{
/// The footprint to sweep: a radius (> 0) or else a polygon in the robot frame; neither when the
/// status is not Ok.
struct CorridorFootprint
{
  double radius = 0.0;
  std::vector<Vec2> polygon;
  CueStatus status;
  bool usable() const { return status.level != CueStatus::Level::Error && (radius > 0.0 || !polygon.empty()); }
};

class CorridorSource
{
public:
  /// Subscribes to `topic` with `nh` (whose callback queue the display drains); empty: none. The
  /// same topic again changes nothing.
  void subscribe(ros::NodeHandle& nh, const std::string& topic);
  void unsubscribe();
  /// Forgets the last message (rviz's Reset).
  void clear();
  /// A round robot.
  static CorridorFootprint fromRadius(double radius);
  /// The typed polygon, read and judged.
  static CorridorFootprint fromText(const std::string& text);
  /// The last message's polygon in `robot_frame` (tf at its stamp, else the latest transform).
  /// Kept per message and Robot frame once it cannot change any more: in the Robot frame itself,
  /// or moved with tf at the message's own (non-zero) stamp. Moved with the latest transform (a
  /// zero or unknown stamp), it is moved again on every call.
  CorridorFootprint fromTopic(const tf2_ros::Buffer& tf, const std::string& robot_frame);
  /// Polygons moved into the Robot frame so far (tests check the cache above).
  std::size_t transforms() const { return transforms_; }
  /// Footprint messages taken so far (tests wait for theirs).
  std::size_t messages() const { return messages_; }
  /// Whether a message arrived since the last call (the picture may change at once).
  bool takeNews() { return news_.take(); }

private:
  void onFootprint(const geometry_msgs::PolygonStamped::ConstPtr& msg);

  TopicSubscription subscription_;
  geometry_msgs::PolygonStamped::ConstPtr last_;
  NewsFlag news_;
  std::size_t messages_ = 0;
  std::size_t transforms_ = 0;
  // fromTopic's last result, while it cannot change: for this message in this frame.
  geometry_msgs::PolygonStamped::ConstPtr kept_message_;
  std::string kept_frame_;
  CorridorFootprint kept_;
};
}  // namespace rviz_projector
