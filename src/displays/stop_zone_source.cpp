#include "rviz_projector/displays/stop_zone_source.h"

#include <cmath>

#include "rviz_projector/displays/ros_clock.h"

namespace rviz_projector
{
void StopZoneSource::subscribe(ros::NodeHandle& nh, const std::string& topic)
{
  if (subscription_.subscribe(nh, topic, 10, &StopZoneSource::onOdometry, this, "Odometry"))
  {
    clear();
  }
}

void StopZoneSource::unsubscribe()
{
  subscription_.shutdown();
  clear();
}

void StopZoneSource::clear()
{
  filter_.clear();
  received_ = false;
  bad_twist_ = false;
}

void StopZoneSource::forgetLaterThan(double now)
{
  if (filter_.empty() || filter_.lastTime() > now)
  {
    clear();
  }
}

void StopZoneSource::onOdometry(const nav_msgs::Odometry::ConstPtr& msg)
{
  const double now = RosClock::shared().policy().rosNow();  // read by the display's drain, before this
  received_ = true;
  news_.raise();
  ++messages_;
  last_arrival_ = now;
  // The twist is in child_frame_id (the robot): its planar norm is the robot's speed in any frame.
  const double vx = msg->twist.twist.linear.x, vy = msg->twist.twist.linear.y;
  bad_twist_ = !std::isfinite(vx) || !std::isfinite(vy);
  if (bad_twist_)
  {
    filter_.clear();  // a later usable message starts afresh
    return;
  }
  // The filter runs on the odometry's own stamps: when the speed was measured, not when it arrived
  // here (transport jitter shifts the bar; a bag replays the same stamps on every pass). A zero
  // stamp, or one the clock makes implausible (older than kStaleAfter, or ahead of the clock by
  // more than kStampAhead: an unsynchronised clock), takes the arrival time instead.
  const double stamp = msg->header.stamp.toSec();
  const bool stamp_usable = stamp > 0.0 && stamp <= now + kStampAhead && now - stamp <= kStaleAfter;
  filter_.add(std::hypot(vx, vy), stamp_usable ? stamp : now);
}

SpeedEstimate StopZoneSource::speedAt(double now)
{
  if (!received_ || bad_twist_ || now - last_arrival_ > kStaleAfter)
  {
    return SpeedEstimate();
  }
  return filter_.at(now);
}

CueStatus StopZoneSource::status(double now) const
{
  if (!subscription_.error().empty())
  {
    return CueStatus{CueStatus::Level::Error, subscription_.error()};
  }
  if (subscription_.topic().empty())
  {
    return CueStatus{CueStatus::Level::Warn, "No Odometry topic set: no stop zone"};
  }
  if (!received_)
  {
    return CueStatus{CueStatus::Level::Warn, "No odometry received yet on " + subscription_.topic() + ": no stop zone"};
  }
  if (bad_twist_)
  {
    return CueStatus{CueStatus::Level::Error,
                     "The odometry's twist on " + subscription_.topic() + " has NaN/Inf values: no stop zone"};
  }
  if (now - last_arrival_ > kStaleAfter)
  {
    // A fixed text: a status that changes every frame repaints rviz's whole property tree.
    return CueStatus{CueStatus::Level::Warn, "No odometry on " + subscription_.topic() + " for more than 1 s: no stop zone"};
  }
  return CueStatus{CueStatus::Level::Ok, "Odometry received on " + subscription_.topic()};
}
}  // namespace rviz_projector
