// Where the time-varying inputs of ProjectedPath's cues come from: the goal's state (an
// actionlib_msgs/GoalStatusArray topic, on the display's private callback queue) and the robot's
// floor position (tf, through rviz's FrameManager). One part of ProjectedPathDisplay: it returns
// the cue input for an instant and what its statuses should say; the display shows them.
#pragma once

#ifndef Q_MOC_RUN
#include <string>
#include <vector>

#include <actionlib_msgs/GoalStatusArray.h>
#include <ros/node_handle.h>
#include <ros/subscriber.h>
#include <ros/time.h>

#include "rviz_projector/core/cue_drawing.h"
#include "rviz_projector/core/goal_cues.h"
#include "rviz_projector/displays/news_flag.h"
#endif

namespace rviz
{
class FrameManager;
}

namespace rviz_projector
{
/// A status line of the cues for the display: empty text = delete the status.
struct CueStatus
{
  enum class Level
  {
    Ok,
    Warn,
    Error,
  };
  Level level = Level::Ok;
  std::string text;
};

class PathCueSource
{
public:
  /// Subscribes to `topic` (empty: none) with `nh` (whose callback queue the display drains).
  void subscribe(ros::NodeHandle& nh, const std::string& topic);
  void unsubscribe();
  bool subscribed() const { return !topic_.empty(); }
  void setParameters(const GoalCueParameters& parameters) { timeline_.setParameters(parameters); }
  /// Forgets the goal's state and the robot's motion (rviz's Reset).
  void clear();

  /// The inputs of the cues at `now`: looks the robot up (`robot_frame` in `fixed_frame`, latest tf)
  /// when `need_robot`, feeds the stillness detector, and asks the timeline for the goal frame.
  PathCueInput inputAt(const ros::Time& now, rviz::FrameManager& frames, const std::string& robot_frame,
                       bool need_robot);

  /// What the "State" status says (no topic: empty text).
  CueStatus stateStatus() const;
  /// What the "Robot" status says (after inputAt; robot not needed: empty text).
  const CueStatus& robotStatus() const { return robot_status_; }
  GoalPhase phase() const { return timeline_.phase(); }
  /// Whether a status message arrived since the last call (the picture may change at once).
  bool takeNews() { return news_.take(); }

private:
  void onStatus(const actionlib_msgs::GoalStatusArray::ConstPtr& msg);

  ros::Subscriber subscriber_;
  std::string topic_;
  std::string subscribe_error_;  // the State topic could not be subscribed (e.g. an invalid name)
  GoalCueTimeline timeline_;
  StillnessDetector stillness_;
  std::vector<GoalStatusEntry> entries_;  // kept between messages (no allocation once big enough)
  GoalSummary summary_;
  bool received_ = false;
  NewsFlag news_;
  bool robot_known_ = false;
  CueStatus robot_status_;
};
}  // namespace rviz_projector
