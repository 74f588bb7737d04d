#include "rviz_projector/displays/path_cue_source.h"
#include "rviz_projector/displays/ros_clock.h"

#include <cmath>

#include <OgreQuaternion.h>
#include <OgreVector3.h>
#include <rviz/frame_manager.h>

namespace rviz_projector
{
namespace
{
const char* phaseName(GoalPhase phase)
{
  switch (phase)
  {
    case GoalPhase::Active:
      return "active";
    case GoalPhase::Failed:
      return "failed (preempted, aborted, rejected, recalled or lost)";
    case GoalPhase::Succeeded:
      return "succeeded";
    case GoalPhase::None:
      break;
  }
  return "none";
}
}  // namespace

void PathCueSource::subscribe(ros::NodeHandle& nh, const std::string& topic)
{
  unsubscribe();
  subscribe_error_.clear();
  topic_ = topic;
  if (topic_.empty())
  {
    return;
  }
  try
  {
    subscriber_ = nh.subscribe(topic_, 10, &PathCueSource::onStatus, this);
  }
  catch (const ros::Exception& e)
  {
    topic_.clear();
    subscribe_error_ = std::string("Cannot subscribe to the State topic '") + topic + "': " + e.what();
  }
}

void PathCueSource::unsubscribe()
{
  subscriber_.shutdown();
  topic_.clear();
  received_ = false;
  summary_ = GoalSummary();
  timeline_.clear();
}

void PathCueSource::clear()
{
  received_ = false;
  summary_ = GoalSummary();
  timeline_.clear();
  stillness_.clear();
}

void PathCueSource::onStatus(const actionlib_msgs::GoalStatusArray::ConstPtr& msg)
{
  entries_.resize(msg->status_list.size());
  for (std::size_t i = 0; i < entries_.size(); ++i)
  {
    const actionlib_msgs::GoalStatus& status = msg->status_list[i];
    entries_[i].id = status.goal_id.id;
    entries_[i].stamp = status.goal_id.stamp.toSec();
    entries_[i].status = status.status;
  }
  summary_ = summarizeGoals(entries_);
  received_ = true;
  news_.raise();
  const double now = RosClock::shared().policy().rosNow();  // read by the display's drain, before this
  timeline_.update(summary_, now, stillness_.still(now));
}

PathCueInput PathCueSource::inputAt(const ros::Time& now, rviz::FrameManager& frames, const std::string& robot_frame,
                                    bool need_robot)
{
  PathCueInput input;
  input.time = now.toSec();
  const bool track = need_robot || timeline_.parameters().warning_enabled;
  robot_status_ = CueStatus();
  if (track)
  {
    Ogre::Vector3 position;
    Ogre::Quaternion orientation;
    if (!robot_frame.empty() && frames.getTransform(robot_frame, ros::Time(), position, orientation) &&
        std::isfinite(position.x) && std::isfinite(position.y))
    {
      input.robot_known = true;
      input.robot = Vec2{position.x, position.y};
      const Ogre::Vector3 forward = orientation * Ogre::Vector3::UNIT_X;  // the robot's x axis on the floor
      input.heading = std::atan2(forward.y, forward.x);
      stillness_.add(input.robot, input.time);
    }
    else
    {
      robot_status_ = CueStatus{CueStatus::Level::Warn,
                                "No transform from the Robot frame '" + robot_frame +
                                    "' to the fixed frame: the horizon and the stop zone start at the path's start, "
                                    "no turn signal, the robot counts as standing still"};
    }
  }
  input.goal = timeline_.frameAt(input.time);
  return input;
}

CueStatus PathCueSource::stateStatus() const
{
  if (!subscribe_error_.empty())
  {
    return CueStatus{CueStatus::Level::Error, subscribe_error_};
  }
  if (topic_.empty())
  {
    return CueStatus();
  }
  if (!received_)
  {
    return CueStatus{CueStatus::Level::Warn,
                     "No goal status received yet on " + topic_ + ": the cues are drawn as for an active goal"};
  }
  if (summary_.phase == GoalPhase::None)
  {
    return CueStatus{CueStatus::Level::Ok, "No goal in the status list"};
  }
  return CueStatus{CueStatus::Level::Ok, "Goal '" + summary_.id + "': " + phaseName(summary_.phase)};
}
}  // namespace rviz_projector
