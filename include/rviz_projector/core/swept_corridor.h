// The floor a robot will sweep (issue 25, ProjectedPath's Corridor): its footprint moved along the
// next metres of its path, as the outer envelope of the footprint's positions. Plain geometry (no
// ROS, no OGRE); the union of the swept pieces is Clipper's (libpolyclipping).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Why a footprint polygon (robot frame: x forward, y left, metres) cannot be swept, or "" when it
/// can: fewer than 3 vertices, a non-finite vertex, no area, edges that cross.
std::string footprintProblem(const std::vector<Vec2>& footprint);

/// A footprint as move_base's `footprint` parameter writes it, "[[x, y], [x, y], ...]" (metres,
/// robot frame); `error` says what is wrong when it cannot be read (the polygon is then empty).
/// The polygon itself is judged by footprintProblem().
std::vector<Vec2> parseFootprint(const std::string& text, std::string& error);

struct CorridorParameters
{
  double length = 3.0;        ///< metres of path from the robot's place (clipped at the destination)
  double edge_width = 0.03;   ///< width of the edge lines, metres, centred on the envelope
  double step = 0.2;          ///< the longest step between two swept positions, metres (exact on straights)
  double turn_step = 0.087;   ///< the largest heading change between two positions, radians (5 degrees)
  double heading_chord = 0.2; ///< the path's heading is that of a chord this long (grid planners zig-zag)
};

/// The swept corridor of the last build():
/// - band(): triangles covering the swept area once (its rims triangulated), for a translucent fill.
/// - edges(): the envelope's boundary without the caps behind the robot and at the far end (the
///   "two outer edges"; where the path loops and the area has holes, the holes' rims too), as
///   polylines, and as triangles of `edge_width` centred on them.
/// Heading along the path: the path's own direction (headingAt over `heading_chord`), not the
/// poses' orientations, which many planners leave unset; so the robot is taken to drive forwards
/// and to turn where the path turns.
class SweptCorridor
{
public:
  /// Sweeps `footprint` (must pass footprintProblem) along the polyline `points` (finite; `lengths`
  /// from accumulateArcLengths) from arc length `start` to start + parameters.length, clipped to the
  /// path's end. An empty or one-point path, a bad footprint, a footprint over 1 km or a corridor
  /// reaching over 1000 km from its start gives nothing.
  void build(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start,
             const std::vector<Vec2>& footprint, const CorridorParameters& parameters);
  /// The same for a round robot of `radius` metres (exact: the path grown by the radius).
  void buildRound(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start, double radius,
                  const CorridorParameters& parameters);

  const std::vector<Vec2>& band() const { return band_; }
  const std::vector<std::vector<Vec2>>& edgeLines() const { return edge_lines_; }
  const std::vector<Vec2>& edges() const { return edge_triangles_; }
  /// How many positions the footprint was placed at in the last build (tests, the benchmark).
  std::size_t positions() const { return placements_.size(); }

  /// A place of the footprint: position relative to the corridor's origin, unit heading.
  struct Placement
  {
    Vec2 position;
    Vec2 forward;
  };

private:
  std::vector<Vec2> band_;
  std::vector<std::vector<Vec2>> edge_lines_;
  std::vector<Vec2> edge_triangles_;
  std::vector<Placement> placements_;
  Vec2 origin_;

  bool begin(const std::vector<Vec2>& points, const std::vector<double>& lengths, double start,
             const CorridorParameters& parameters);
  /// `rims`: the union's rims (outer ones counter-clockwise); `sides`: the footprint's start left,
  /// start right, end left and end right points (robot frame).
  void finish(const std::vector<std::vector<Vec2>>& rims, const std::array<Vec2, 4>& sides,
              const CorridorParameters& parameters);
};
}  // namespace rviz_projector
