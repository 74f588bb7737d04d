// The arrows and destination circle of a spaced path as visualization_msgs markers, for
// path_to_markers: what the ProjectedPath display draws, in a form stock rviz, other viewers and
// rosbag understand.
#pragma once

#include <cstddef>

#include <std_msgs/ColorRGBA.h>
#include <std_msgs/Header.h>
#include <visualization_msgs/MarkerArray.h>

#include "rviz_projector/core/path_style_limits.h"
#include "rviz_projector/core/spaced_path.h"
#include "rviz_projector/core/spacing_parameters.h"

namespace rviz_projector
{
struct PathMarkerStyle
{
  std_msgs::ColorRGBA arrow_color;   // defaults: magenta arrows,
  std_msgs::ColorRGBA circle_color;  // green circle, as the ProjectedPath display
  /// z of the drawing in the marker frame, metres (the display's "Height above floor").
  double height = path_style::kDefaultHeight;

  PathMarkerStyle();
};

/**
 * Builds one MarkerArray per path. Arrow k (0 = nearest the destination) is an ARROW marker in
 * namespace "arrows" with id k and `points` = {tail, tip}; scale.x = shaft diameter, scale.y = head
 * diameter, scale.z = head length, so stock rviz draws exactly the given head. The destination is a
 * thin CYLINDER in namespace "destination", id 0, scale.x = scale.y = circle diameter.
 *
 * The builder remembers what it published: markers of the previous path that the new one no longer
 * has are DELETEd in the same array, so a shorter path leaves no stale arrows and an empty path
 * clears everything. The very first array starts with DELETEALL, which also clears what an earlier
 * run of the node left in a viewer.
 */
class PathMarkers
{
public:
  static constexpr const char* kArrowNamespace = "arrows";
  static constexpr const char* kDestinationNamespace = "destination";
  /// Arrows sit this much above the circle, as in the display.
  static constexpr double kArrowLift = 0.001;
  /// Height of the destination cylinder: a flat disc.
  static constexpr double kCircleThickness = 0.002;

  void setStyle(const PathMarkerStyle& style) { style_ = style; }
  const PathMarkerStyle& style() const { return style_; }

  /// Markers for `path` (spaced with `parameters`) in `header`'s frame and stamp.
  const visualization_msgs::MarkerArray& update(const SpacedPath& path, const SpacingParameters& parameters,
                                                const std_msgs::Header& header);

private:
  PathMarkerStyle style_;
  visualization_msgs::MarkerArray array_;
  // What the previous array published: the arrows and destination of that path that the next one
  // no longer has are DELETEd (see update()).
  std::size_t published_arrows_ = 0;
  bool published_destination_ = false;
  bool first_ = true;
};
}  // namespace rviz_projector
