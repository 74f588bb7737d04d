// Where the stop zone's speed comes from: a nav_msgs/Odometry topic (on the display's private
// callback queue), its twist checked and smoothed by the core's SpeedFilter. One part of
// ProjectedPathDisplay: it returns the speed for an instant and what the "Stop zone" status says.
#pragma once

#ifndef Q_MOC_RUN
#include <string>

#include <nav_msgs/Odometry.h>
#include <ros/node_handle.h>
#include <ros/subscriber.h>

#include "rviz_projector/core/stop_zone.h"
#include "rviz_projector/displays/news_flag.h"
#include "rviz_projector/displays/path_cue_source.h"
#include "rviz_projector/displays/topic_subscription.h"
#endif

namespace rviz_projector
{
class StopZoneSource
{
public:
  /// Odometry older than this (ROS time since it arrived) is stale: no stop zone.
  static constexpr double kStaleAfter = 1.0;
  /// A stamp at most this far ahead of the clock still counts as the speed's measurement time.
  static constexpr double kStampAhead = 0.1;

  /// Subscribes to `topic` with `nh` (whose callback queue the display drains); empty: none. The
  /// same topic again changes nothing.
  void subscribe(ros::NodeHandle& nh, const std::string& topic);
  void unsubscribe();
  /// Forgets the speed and every message (a new topic; forgetLaterThan below for Reset and jumps).
  void clear();
  /// rviz's Reset, or ROS time jumping back (a bag loop): forgets odometry measured after `now`
  /// (of before the jump) and keeps what was measured on the current time line, so the filter
  /// does not depend on which of the new pass's messages arrived before the reset did.
  void forgetLaterThan(double now);

  /// The filtered speed at `now` (ROS time, seconds); standing (no zone) without fresh, usable
  /// odometry.
  SpeedEstimate speedAt(double now);
  /// What the "Stop zone" status says at `now` (empty text: the stop zone is off).
  CueStatus status(double now) const;
  /// Odometry messages taken so far (tests wait for theirs).
  std::size_t messages() const { return messages_; }
  /// Whether a message arrived since the last call (the picture may change at once).
  bool takeNews() { return news_.take(); }

private:
  void onOdometry(const nav_msgs::Odometry::ConstPtr& msg);

  TopicSubscription subscription_;
  SpeedFilter filter_;
  bool received_ = false;
  bool bad_twist_ = false;    // the last message's twist had NaN/Inf
  double last_arrival_ = 0.0; // ROS time of the last message
  NewsFlag news_;
  std::size_t messages_ = 0;
};
}  // namespace rviz_projector
