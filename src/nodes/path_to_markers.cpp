// path_to_markers: the ProjectedPath display's arrows and destination circle as a
// visualization_msgs/MarkerArray, for users of the reference workflow (a MarkerArray shown by a
// camera-like display), other viewers, and recording.
//
// Spacing is computed by the same core as the display (rviz_projector::PathSpacer) with the same
// parameters, so both show the same arrows. Arrows are ARROW markers with points (tail, tip) and
// scale = (shaft diameter, head diameter, head length), which stock rviz draws with exactly the
// given head. Markers a shorter path no longer needs are deleted; an empty path clears them all.
//
// Subscribes: path     nav_msgs/Path
// Publishes:  markers  visualization_msgs/MarkerArray (latched: a late viewer gets the current set)
// Parameters: ~spacing_mode (exact|paper), ~spacing, ~shaft_length, ~shaft_diameter, ~head_length,
//             ~head_diameter, ~circle_diameter (metres), ~arrow_color, ~circle_color ([r, g, b] or
//             [r, g, b, a], 0..1), ~height (metres above z = 0 of the marker frame),
//             ~target_frame (frame to draw in; empty: the path's own frame), ~transform_timeout (s).

#include <nav_msgs/Path.h>
#include <ros/ros.h>
#include <tf2/exceptions.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>
#include <visualization_msgs/MarkerArray.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rviz_projector/core/ascii_lower.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/path_style_limits.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/ros/ros_conversions.h"
#include "rviz_projector/nodes/path_markers.h"

namespace rviz_projector
{
namespace
{
const char* const kName = "path_to_markers";
// Limits of the ProjectedPath display's properties (shared: core/path_style_limits.h).
using path_style::kMaxHeight;
using path_style::kMaxSize;
using path_style::kMaxSpacing;
using path_style::kMinSize;
using path_style::kMinSpacing;
constexpr double kWarnPeriod = 5.0;  // seconds between repeated warnings

bool isNumber(const XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeDouble || value.getType() == XmlRpc::XmlRpcValue::TypeInt;
}

double toDouble(XmlRpc::XmlRpcValue& value)
{
  return value.getType() == XmlRpc::XmlRpcValue::TypeInt ? static_cast<int>(value) : static_cast<double>(value);
}

/// A number parameter: the fallback when unset, wrong-typed or not finite; clamped to [low, high].
double numberParam(const ros::NodeHandle& pnh, const std::string& name, double fallback, double low, double high)
{
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam(name, value))
  {
    return fallback;
  }
  if (!isNumber(value) || !std::isfinite(toDouble(value)))
  {
    ROS_WARN("%s: ~%s must be a number, using %g", kName, name.c_str(), fallback);
    return fallback;
  }
  const double number = toDouble(value);
  const double clamped = std::min(high, std::max(low, number));
  if (clamped != number)
  {
    ROS_WARN("%s: ~%s = %g is outside [%g, %g], using %g", kName, name.c_str(), number, low, high, clamped);
  }
  return clamped;
}

/// A colour parameter: [r, g, b] or [r, g, b, a] with components in 0..1.
std_msgs::ColorRGBA colorParam(const ros::NodeHandle& pnh, const std::string& name, const std_msgs::ColorRGBA& fallback)
{
  XmlRpc::XmlRpcValue value;
  if (!pnh.getParam(name, value))
  {
    return fallback;
  }
  const bool list = value.getType() == XmlRpc::XmlRpcValue::TypeArray && (value.size() == 3 || value.size() == 4);
  bool numbers = list;
  for (int i = 0; numbers && i < value.size(); ++i)
  {
    numbers = isNumber(value[i]) && std::isfinite(toDouble(value[i]));
  }
  if (!numbers)
  {
    ROS_WARN("%s: ~%s must be a list [r, g, b] or [r, g, b, a] of numbers in 0..1, using [%g, %g, %g, %g]", kName,
             name.c_str(), fallback.r, fallback.g, fallback.b, fallback.a);
    return fallback;
  }
  float c[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  bool clamped = false;
  for (int i = 0; i < value.size(); ++i)
  {
    const double v = toDouble(value[i]);
    c[i] = static_cast<float>(std::min(1.0, std::max(0.0, v)));
    clamped = clamped || c[i] != static_cast<float>(v);
  }
  if (clamped)
  {
    ROS_WARN("%s: ~%s has components outside 0..1, using [%g, %g, %g, %g]", kName, name.c_str(), c[0], c[1], c[2],
             c[3]);
  }
  std_msgs::ColorRGBA color;
  color.r = c[0];
  color.g = c[1];
  color.b = c[2];
  color.a = c[3];
  return color;
}

SpacingMode modeParam(const ros::NodeHandle& pnh)
{
  const std::string mode = asciiLower(pnh.param<std::string>("spacing_mode", "exact"));
  if (mode == "paper")
  {
    return SpacingMode::Paper;
  }
  if (mode != "exact")
  {
    ROS_WARN("%s: ~spacing_mode '%s' is neither 'exact' nor 'paper', using exact", kName, mode.c_str());
  }
  return SpacingMode::Exact;
}

class PathToMarkers
{
public:
  PathToMarkers(const ros::NodeHandle& nh, const ros::NodeHandle& pnh) : nh_(nh)
  {
    SpacingParameters p;
    p.mode = modeParam(pnh);
    p.spacing = numberParam(pnh, "spacing", p.spacing, kMinSpacing, kMaxSpacing);
    p.arrow.shaft_length = numberParam(pnh, "shaft_length", p.arrow.shaft_length, kMinSize, kMaxSize);
    p.arrow.shaft_diameter = numberParam(pnh, "shaft_diameter", p.arrow.shaft_diameter, kMinSize, kMaxSize);
    p.arrow.head_length = numberParam(pnh, "head_length", p.arrow.head_length, kMinSize, kMaxSize);
    p.arrow.head_diameter = numberParam(pnh, "head_diameter", p.arrow.head_diameter, kMinSize, kMaxSize);
    p.circle_diameter = numberParam(pnh, "circle_diameter", p.circle_diameter, kMinSize, kMaxSize);
    spacer_.setParameters(p);
    if (p.mode == SpacingMode::Exact && p.spacing < p.arrow.length())
    {
      ROS_WARN("%s: ~spacing %g m is shorter than an arrow (shaft + head = %g m): arrows overlap", kName, p.spacing,
               p.arrow.length());
    }
    if (p.arrow.head_diameter < p.arrow.shaft_diameter)
    {
      ROS_WARN("%s: ~head_diameter %g m is narrower than ~shaft_diameter %g m: arrows lose their heads", kName,
               p.arrow.head_diameter, p.arrow.shaft_diameter);
    }

    PathMarkerStyle style;
    style.arrow_color = colorParam(pnh, "arrow_color", style.arrow_color);
    style.circle_color = colorParam(pnh, "circle_color", style.circle_color);
    style.height = numberParam(pnh, "height", style.height, -kMaxHeight, kMaxHeight);
    markers_.setStyle(style);

    target_frame_ = pnh.param<std::string>("target_frame", "");
    transform_timeout_ = numberParam(pnh, "transform_timeout", 0.1, 0.0, 10.0);
    if (!target_frame_.empty())
    {
      tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
      tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_, nh_);
    }

    publisher_ = nh_.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
    subscriber_ = nh_.subscribe("path", 1, &PathToMarkers::onPath, this);
    ROS_INFO("%s: %s -> %s, %s spacing %g m, arrows %g + %g m long, %g / %g m wide, circle %g m, frame %s", kName,
             subscriber_.getTopic().c_str(), publisher_.getTopic().c_str(),
             p.mode == SpacingMode::Paper ? "paper" : "exact", p.spacing, p.arrow.shaft_length, p.arrow.head_length,
             p.arrow.shaft_diameter, p.arrow.head_diameter, p.circle_diameter,
             target_frame_.empty() ? "of the path" : target_frame_.c_str());
  }

private:
  void onPath(const nav_msgs::Path::ConstPtr& msg)
  {
    std_msgs::Header header = msg->header;
    if (!target_frame_.empty())
    {
      header.frame_id = target_frame_;
    }
    if (msg->poses.empty())
    {
      publish(header);  // clears the markers; needs neither a frame nor tf
      return;
    }
    if (header.frame_id.empty())
    {
      ROS_WARN_THROTTLE(kWarnPeriod, "%s: the path has no frame_id and ~target_frame is not set: nothing published",
                        kName);
      return;
    }
    RigidTransform to_target;  // identity when drawing in the path's own frame
    if (!target_frame_.empty() && msg->header.frame_id != target_frame_)
    {
      try
      {
        to_target = toRigidTransform(tf_buffer_->lookupTransform(target_frame_, msg->header.frame_id,
                                                                 msg->header.stamp, ros::Duration(transform_timeout_))
                                         .transform);
      }
      catch (const tf2::TransformException& e)
      {
        ROS_WARN_THROTTLE(kWarnPeriod, "%s: cannot transform the path from '%s' to '%s': %s (nothing published)",
                          kName, msg->header.frame_id.c_str(), target_frame_.c_str(), e.what());
        return;
      }
    }

    const std::size_t dropped = pathToFloorPoints(*msg, to_target, points_);
    if (dropped > 0)
    {
      ROS_WARN_THROTTLE(kWarnPeriod, "%s: %zu of %zu path poses have NaN/Inf or out-of-range values and were dropped", kName, dropped,
                        msg->poses.size());
    }
    publish(header);
  }

  void publish(const std_msgs::Header& header)
  {
    const SpacedPath& spaced = spacer_.space(points_);
    if (spaced.truncated)
    {
      ROS_WARN_THROTTLE(kWarnPeriod, "%s: path too long for the spacing: only the %zu arrows nearest the "
                        "destination are published", kName, spaced.arrows.size());
    }
    publisher_.publish(markers_.update(spaced, spacer_.parameters(), header));
    points_.clear();
  }

  ros::NodeHandle nh_;
  ros::Publisher publisher_;
  ros::Subscriber subscriber_;
  std::string target_frame_;
  double transform_timeout_ = 0.1;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  PathSpacer spacer_;
  PathMarkers markers_;
  std::vector<Vec2> points_;
};
}  // namespace
}  // namespace rviz_projector

int main(int argc, char** argv)
{
  ros::init(argc, argv, "path_to_markers");
  rviz_projector::PathToMarkers node{ros::NodeHandle(), ros::NodeHandle("~")};
  ros::spin();
  return 0;
}
