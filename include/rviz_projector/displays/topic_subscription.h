// The subscription of a cue part whose topic is a property: the same topic again changes nothing, a
// topic ROS refuses leaves an error text for the part's status. Shared by the Stop zone's and the
// Corridor's sources.
#pragma once

#ifndef Q_MOC_RUN
#include <cstdint>
#include <string>

#include <boost/shared_ptr.hpp>
#include <ros/node_handle.h>
#include <ros/subscriber.h>
#endif

namespace rviz_projector
{
class TopicSubscription
{
public:
  /// Subscribes `object`'s `callback` to `topic` (empty: none) with `nh`; `what` names the topic in
  /// the error ("Odometry"). False when nothing changed (the same topic, subscribed); true when the
  /// old subscription was dropped, so the caller forgets what it had.
  template <class Message, class Object>
  bool subscribe(ros::NodeHandle& nh, const std::string& topic, std::uint32_t queue,
                 void (Object::*callback)(const boost::shared_ptr<const Message>&), Object* object, const char* what)
  {
    if (topic == topic_ && error_.empty())
    {
      return false;
    }
    shutdown();
    topic_ = topic;
    if (topic_.empty())
    {
      return true;
    }
    try
    {
      subscriber_ = nh.subscribe(topic_, queue, callback, object);
    }
    catch (const ros::Exception& e)
    {
      topic_.clear();
      error_ = std::string("Cannot subscribe to the ") + what + " topic '" + topic + "': " + e.what();
    }
    return true;
  }

  void shutdown()
  {
    subscriber_.shutdown();
    topic_.clear();
    error_.clear();
  }

  /// The topic subscribed to (empty: none).
  const std::string& topic() const { return topic_; }
  /// Why the last topic could not be subscribed to (empty: it could, or there was none).
  const std::string& error() const { return error_; }

private:
  ros::Subscriber subscriber_;
  std::string topic_;
  std::string error_;
};
}  // namespace rviz_projector
