#include "rviz_projector/displays/corridor_source.h"

#include <cmath>

#include <tf2/exceptions.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <tf2_ros/buffer.h>

#include "rviz_projector/core/swept_corridor.h"

namespace rviz_projector
{
namespace
{
CorridorFootprint judged(std::vector<Vec2> polygon, const std::string& where)
{
  CorridorFootprint result;
  const std::string problem = footprintProblem(polygon);
  if (!problem.empty())
  {
    result.status = CueStatus{CueStatus::Level::Error, where + ": " + problem + ": no corridor"};
    return result;
  }
  result.polygon = std::move(polygon);
  result.status = CueStatus{CueStatus::Level::Ok, where + ": " + std::to_string(result.polygon.size()) + " points"};
  return result;
}
}  // namespace

void CorridorSource::subscribe(ros::NodeHandle& nh, const std::string& topic)
{
  if (subscription_.subscribe(nh, topic, 2, &CorridorSource::onFootprint, this, "Footprint"))
  {
    clear();
  }
}

void CorridorSource::unsubscribe()
{
  subscription_.shutdown();
  clear();
}

void CorridorSource::clear()
{
  last_.reset();
  kept_message_.reset();
}

void CorridorSource::onFootprint(const geometry_msgs::PolygonStamped::ConstPtr& msg)
{
  last_ = msg;
  news_.raise();
  ++messages_;
}

CorridorFootprint CorridorSource::fromRadius(double radius)
{
  CorridorFootprint result;
  if (!(radius > 0.0) || !std::isfinite(radius))
  {
    result.status = CueStatus{CueStatus::Level::Error, "The Radius must be > 0: no corridor"};
    return result;
  }
  result.radius = radius;
  result.status = CueStatus{CueStatus::Level::Ok, "A round robot"};
  return result;
}

CorridorFootprint CorridorSource::fromText(const std::string& text)
{
  std::string error;
  std::vector<Vec2> polygon = parseFootprint(text, error);
  if (!error.empty())
  {
    CorridorFootprint result;
    result.status = CueStatus{CueStatus::Level::Error, "Polygon: " + error + ": no corridor"};
    return result;
  }
  return judged(std::move(polygon), "Polygon");
}

CorridorFootprint CorridorSource::fromTopic(const tf2_ros::Buffer& tf, const std::string& robot_frame)
{
  CorridorFootprint result;
  if (!subscription_.error().empty())
  {
    result.status = CueStatus{CueStatus::Level::Error, subscription_.error()};
    return result;
  }
  const std::string& topic = subscription_.topic();
  if (topic.empty())
  {
    result.status = CueStatus{CueStatus::Level::Warn, "No Footprint topic set: no corridor"};
    return result;
  }
  if (!last_)
  {
    result.status = CueStatus{CueStatus::Level::Warn, "No footprint received yet on " + topic + ": no corridor"};
    return result;
  }
  if (kept_message_ == last_ && kept_frame_ == robot_frame)
  {
    return kept_;  // this runs every frame; the message's outline at its stamp does not change
  }
  // move_base publishes the outline where the robot was at the stamp, in the costmap's frame: at
  // that stamp it is the robot's own outline. A stamp tf cannot give (zero, too old) takes the latest.
  geometry_msgs::TransformStamped to_robot;
  bool at_stamp = !last_->header.stamp.isZero();
  try
  {
    try
    {
      to_robot = tf.lookupTransform(robot_frame, last_->header.frame_id, last_->header.stamp);
    }
    catch (const tf2::TransformException&)
    {
      at_stamp = false;
      to_robot = tf.lookupTransform(robot_frame, last_->header.frame_id, ros::Time(0));
    }
  }
  catch (const tf2::TransformException& e)
  {
    result.status = CueStatus{CueStatus::Level::Error, "Footprint on " + topic + ": no transform from '" +
                                                           last_->header.frame_id + "' to the Robot frame '" +
                                                           robot_frame + "': " + e.what() + ": no corridor"};
    return result;
  }
  std::vector<Vec2> polygon;
  for (const geometry_msgs::Point32& p : last_->polygon.points)
  {
    geometry_msgs::Point in, out;
    in.x = p.x;
    in.y = p.y;
    in.z = p.z;
    tf2::doTransform(in, out, to_robot);
    polygon.push_back({out.x, out.y});
  }
  ++transforms_;
  result = judged(std::move(polygon), "Footprint on " + topic);
  const auto bare = [](const std::string& frame) { return frame.rfind('/', 0) == 0 ? frame.substr(1) : frame; };
  if (at_stamp || bare(last_->header.frame_id) == bare(robot_frame))
  {
    kept_message_ = last_;
    kept_frame_ = robot_frame;
    kept_ = result;
  }
  return result;
}
}  // namespace rviz_projector
