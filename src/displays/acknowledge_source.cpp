#include "rviz_projector/displays/acknowledge_source.h"

#include <algorithm>
#include <cstddef>

#include <OgreQuaternion.h>
#include <OgreVector3.h>
#include <rviz/frame_manager.h>

#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/displays/ros_clock.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
RigidTransform fromOgre(const Ogre::Vector3& p, const Ogre::Quaternion& q)
{
  return RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, Vec3{p.x, p.y, p.z});
}

CueStatus nobody(CueStatus::Level level, const std::string& why)
{
  return CueStatus{level, why + ": nobody is acknowledged"};
}

/// tf missing: an error, but a warning saying why right after a backward jump of ROS time (rviz's
/// tf buffer is empty until a bag replays the transforms).
CueStatus noTransform(const std::string& why)
{
  if (RosClock::shared().policy().justStartedOrJumpedBack())
  {
    return nobody(CueStatus::Level::Warn, kWaitingForTfAfterJump + why);
  }
  return nobody(CueStatus::Level::Error, why);
}
}  // namespace

void AcknowledgeSource::subscribe(ros::NodeHandle& nh, const std::string& topic)
{
  if (subscription_.subscribe(nh, topic, 2, &AcknowledgeSource::onPath, this, "Path"))
  {
    path_.reset();
  }
}

void AcknowledgeSource::unsubscribe()
{
  subscription_.shutdown();
  clear();
}

void AcknowledgeSource::clear()
{
  path_.reset();
  tracker_.clear();
  clusters_.clear();
  scan_seen_ = false;
  clusters_found_ = 0;
  frame_.triangles.clear();
  frame_.alpha.clear();
  frame_.acknowledged = 0;
}

void AcknowledgeSource::onPath(const nav_msgs::Path::ConstPtr& msg)
{
  path_ = msg;
  news_.raise();
  ++path_messages_;
}

void AcknowledgeSource::addScan(const std::vector<Vec2>& points, double stamp, const ClusterLimits& limits,
                                const TrackerParameters& tracker)
{
  findPersonClusters(points, limits, clusters_);
  clusters_found_ = clusters_.size();
  if (clusters_.size() > kMaxPeople)
  {
    clusters_.resize(kMaxPeople);
  }
  tracker_.update(clusters_, stamp, tracker);
  scan_seen_ = true;
}

void AcknowledgeSource::scanLost(double now, const TrackerParameters& tracker)
{
  clusters_.clear();
  // Nobody is seen from now on; the fade counts from when each was last seen.
  tracker_.update(clusters_, std::max(now, 0.0), tracker);
  scan_seen_ = false;
}

bool AcknowledgeSource::pathPoints(rviz::FrameManager& frames, CueStatus& status)
{
  const std::string& topic = subscription_.topic();
  if (!subscription_.error().empty())
  {
    status = CueStatus{CueStatus::Level::Error, subscription_.error()};
    return false;
  }
  if (topic.empty())
  {
    status = nobody(CueStatus::Level::Warn, "No Path topic set");
    return false;
  }
  if (!path_)
  {
    status = nobody(CueStatus::Level::Warn, "No path received yet on " + topic);
    return false;
  }
  Ogre::Vector3 position;
  Ogre::Quaternion orientation;
  if (!frames.getTransform(path_->header.frame_id, ros::Time(), position, orientation))
  {
    status = noTransform("No transform from the path's frame '" + path_->header.frame_id + "'");
    return false;
  }
  const std::size_t dropped = pathToFloorPoints(*path_, fromOgre(position, orientation), path_points_);
  if (path_points_.empty())
  {
    status = nobody(CueStatus::Level::Warn,
                    "The path on " + topic + " has no usable pose (" + std::to_string(dropped) + " NaN/Inf or too far)");
    return false;
  }
  if (dropped > 0)
  {
    status.text = ", " + std::to_string(dropped) + " path poses with NaN/Inf or too far skipped";
    status.level = CueStatus::Level::Warn;
  }
  return true;
}

const AcknowledgeFrame& AcknowledgeSource::build(double now, rviz::FrameManager& frames, const std::string& robot_frame,
                                                 const AcknowledgeParameters& arc, const TrackerParameters& tracker,
                                                 double feet_margin)
{
  frame_.triangles.clear();
  frame_.alpha.clear();
  frame_.acknowledged = 0;
  CueStatus path_note;
  if (!pathPoints(frames, path_note))
  {
    frame_.status = path_note;
    return frame_;
  }
  Ogre::Vector3 position;
  Ogre::Quaternion orientation;
  if (robot_frame.empty() || !frames.getTransform(robot_frame, ros::Time(), position, orientation))
  {
    frame_.status = noTransform("No transform from the Robot frame '" + robot_frame + "'");
    return frame_;
  }
  if (!scan_seen_ && tracker_.tracks().empty())
  {
    frame_.status = nobody(CueStatus::Level::Warn, "No scan received yet");
    return frame_;
  }
  const Vec2 robot{position.x, position.y};
  const PathAheadStart start = locatePathAhead(path_points_, robot);  // once for everyone
  std::string refusal;
  for (const PersonTrack& track : tracker_.tracks())
  {
    const double opacity = PersonTracker::opacity(track, now, tracker);
    if (!(opacity > 0.0))
    {
      continue;
    }
    const std::size_t before = frame_.triangles.size();
    const AcknowledgeResult r =
        acknowledgeArc(track.position, track.radius + feet_margin, robot, path_points_, start, arc, frame_.triangles);
    if (r.drawn)
    {
      ++frame_.acknowledged;
      frame_.alpha.resize(frame_.triangles.size(), 1.0f);
      std::fill(frame_.alpha.begin() + static_cast<std::ptrdiff_t>(before), frame_.alpha.end(),
                static_cast<float>(opacity));
    }
    else if (r.reason != "out of Range of the path ahead")
    {
      refusal = r.reason;
    }
  }
  // A fixed text for a given count: a status that changes every frame repaints rviz's property tree.
  std::string text = std::to_string(frame_.acknowledged) + " of " + std::to_string(tracker_.tracks().size()) +
                     " people acknowledged (the others are out of Range of the path ahead)";
  CueStatus::Level level = path_note.level;
  if (!refusal.empty())
  {
    text += "; not drawn: " + refusal;
    level = CueStatus::Level::Warn;
  }
  if (clusters_found_ > kMaxPeople)
  {
    text += "; only the first " + std::to_string(kMaxPeople) + " of " + std::to_string(clusters_found_) +
            " person-sized clusters are tracked";
    level = CueStatus::Level::Warn;
  }
  frame_.status = CueStatus{level, text + path_note.text};
  return frame_;
}
}  // namespace rviz_projector
