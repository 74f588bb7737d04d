// The "I have seen you" cue of ProjectionMask (issue 25, part 4): an arc on the floor on the
// robot's side of a person near the path ahead, and optionally a short arrow showing which side of
// them the path passes. Plain geometry (no ROS, no OGRE).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
struct AcknowledgeParameters
{
  double range = 1.5;          ///< metres: people further than this from the path ahead get no arc
  double distance = 0.2;       ///< metres from the edge of the person's feet (see feet_radius) to the arc's inner edge
  double arc_angle = 2.0944;   ///< radians the arc spans (120 degrees), centred on the direction to the robot
  double line_width = 0.05;    ///< metres: the arc's width (radially) and the arrow's shaft width
  bool side_arrow = false;     ///< also draw the arrow showing the side the path passes on
};

/// The largest coordinate or length accepted (metres); beyond it nothing is drawn.
constexpr double kAcknowledgeMaxMetres = 1e5;
/// The arc is drawn as segments of at most this angle (radians, 5 degrees).
constexpr double kAcknowledgeArcStep = 0.0872665;
/// The side arrow's length (metres, along the path). Its centre line runs 2 x line_width beyond the
/// arc's outer radius; shaft line_width wide, head 3 x line_width long and wide.
constexpr double kSideArrowLength = 0.3;

/// What acknowledgeArc did for one person.
struct AcknowledgeResult
{
  bool drawn = false;          ///< triangles were appended
  std::string reason;          ///< why not (empty when drawn)
  double path_distance = 0.0;  ///< from the person's centre to the path ahead, metres (when computed)
  Vec2 closest;                ///< the point of the path ahead nearest the person
  int side = 0;                ///< +1: the person is left of the path (it passes on their right, seen
                               ///< along the path), -1: right, 0: on the path (no arrow)
  double inner_radius = 0.0;   ///< of the arc, from the person's centre
  double outer_radius = 0.0;
};

/**
 * For a person at `person` whose masked feet reach `feet_radius` from there (the display passes the
 * cluster's radius + the mask's Margin x sqrt(2), the corner of its square columns), the robot at
 * `robot` and the planned path `path` (fixed frame, metres): the path ahead is the polyline from the
 * point of `path` nearest the robot onward. When the person's centre is within `range` of it, appends
 * to `triangles` (3 vertices each, counter-clockwise seen from above) an annulus sector centred on
 * the person: inner radius feet_radius + distance, outer radius inner + line_width, spanning
 * arc_angle, centred on the direction from the person to the robot; so it never touches the masked
 * feet. With side_arrow (and the person off the path), an arrow along the path's direction at the
 * closest point, beside the person on the path's side, its centre line 2 x line_width beyond the
 * outer radius (no part of it nearer the person than the outer radius): which side of them the
 * robot passes. Bad input (NaN, a path of no point, values beyond kAcknowledgeMaxMetres,
 * a robot on the person's centre, line_width or arc_angle <= 0) appends nothing and says why.
 */
AcknowledgeResult acknowledgeArc(const Vec2& person, double feet_radius, const Vec2& robot,
                                 const std::vector<Vec2>& path, const AcknowledgeParameters& parameters,
                                 std::vector<Vec2>& triangles);

/// Where the path ahead starts: the point of `path` nearest the robot and its segment (the first
/// of equally near ones). Not valid (with the problem) for a path of no point, a path with NaN/Inf
/// or points beyond kAcknowledgeMaxMetres, or a robot place like that. One per scan, for everyone.
struct PathAheadStart
{
  bool valid = false;
  std::string problem;
  std::size_t segment = 0;
  Vec2 point;
};
PathAheadStart locatePathAhead(const std::vector<Vec2>& path, const Vec2& robot);

/// acknowledgeArc with the path ahead's start already located (locatePathAhead(path, robot)).
AcknowledgeResult acknowledgeArc(const Vec2& person, double feet_radius, const Vec2& robot,
                                 const std::vector<Vec2>& path, const PathAheadStart& start,
                                 const AcknowledgeParameters& parameters, std::vector<Vec2>& triangles);
}  // namespace rviz_projector
