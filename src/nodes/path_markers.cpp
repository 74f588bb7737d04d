#include "rviz_projector/nodes/path_markers.h"

namespace rviz_projector
{
namespace
{
std_msgs::ColorRGBA rgba(float r, float g, float b, float a)
{
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

visualization_msgs::Marker baseMarker(const std_msgs::Header& header, const char* ns, int id, int action)
{
  visualization_msgs::Marker marker;
  marker.header = header;
  marker.ns = ns;
  marker.id = id;
  marker.action = action;
  marker.pose.orientation.w = 1.0;
  return marker;
}

geometry_msgs::Point point(const Vec2& p, double z)
{
  geometry_msgs::Point q;
  q.x = p.x;
  q.y = p.y;
  q.z = z;
  return q;
}
}  // namespace

PathMarkerStyle::PathMarkerStyle() : arrow_color(rgba(1.0f, 0.0f, 1.0f, 1.0f)), circle_color(rgba(0.0f, 1.0f, 0.0f, 1.0f))
{
}

const visualization_msgs::MarkerArray& PathMarkers::update(const SpacedPath& path, const SpacingParameters& parameters,
                                                           const std_msgs::Header& header)
{
  array_.markers.clear();
  array_.markers.reserve(path.arrows.size() + published_arrows_ + 2);
  if (first_)
  {
    array_.markers.push_back(baseMarker(header, "", 0, visualization_msgs::Marker::DELETEALL));
    first_ = false;
  }

  const ArrowDimensions& arrow = parameters.arrow;
  for (std::size_t k = 0; k < path.arrows.size(); ++k)
  {
    visualization_msgs::Marker marker =
        baseMarker(header, kArrowNamespace, static_cast<int>(k), visualization_msgs::Marker::ADD);
    marker.type = visualization_msgs::Marker::ARROW;
    marker.points.push_back(point(path.arrows[k].tail, style_.height + kArrowLift));
    marker.points.push_back(point(path.arrows[k].tip, style_.height + kArrowLift));
    marker.scale.x = arrow.shaft_diameter;
    marker.scale.y = arrow.head_diameter;
    marker.scale.z = arrow.head_length;
    marker.color = style_.arrow_color;
    array_.markers.push_back(marker);
  }
  for (std::size_t k = path.arrows.size(); k < published_arrows_; ++k)
  {
    array_.markers.push_back(
        baseMarker(header, kArrowNamespace, static_cast<int>(k), visualization_msgs::Marker::DELETE));
  }
  published_arrows_ = path.arrows.size();

  if (path.has_destination)
  {
    visualization_msgs::Marker marker = baseMarker(header, kDestinationNamespace, 0, visualization_msgs::Marker::ADD);
    marker.type = visualization_msgs::Marker::CYLINDER;
    marker.pose.position = point(path.destination, style_.height);
    marker.scale.x = parameters.circle_diameter;
    marker.scale.y = parameters.circle_diameter;
    marker.scale.z = kCircleThickness;
    marker.color = style_.circle_color;
    array_.markers.push_back(marker);
  }
  else if (published_destination_)
  {
    array_.markers.push_back(baseMarker(header, kDestinationNamespace, 0, visualization_msgs::Marker::DELETE));
  }
  published_destination_ = path.has_destination;
  return array_;
}
}  // namespace rviz_projector
