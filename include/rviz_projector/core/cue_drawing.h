// What ProjectedPath draws at one instant once its cues are applied: the arrows inside the horizon
// (fading ones with their opacity), the destination as circle or cross, and the turn-signal glyph.
// Plain geometry (no ROS, no OGRE): the display hands the buffers to its meshes.
#pragma once

#include <cstddef>
#include <vector>

#include "rviz_projector/core/goal_cues.h"
#include "rviz_projector/core/spaced_path.h"
#include "rviz_projector/core/spacing_parameters.h"
#include "rviz_projector/core/stop_zone.h"
#include "rviz_projector/core/swept_corridor.h"
#include "rviz_projector/core/turn_signal.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// The cue settings of ProjectedPath (its properties). Everything off by default.
struct PathCueSettings
{
  bool horizon = false;
  double horizon_length = 3.0;  ///< metres of path ahead of the robot
  double fade_length = 1.0;     ///< the last metres of the horizon fade out
  bool marching = false;
  double marching_speed = 0.3;  ///< m/s towards the destination
  bool turn_signal = false;
  TurnSignalParameters turn;
  double turn_hz = 1.5;         ///< blink frequency of the glyph
  double glyph_size = 0.3;      ///< metres across
  double glyph_ahead = 0.8;     ///< from the robot's centre to the glyph's centre, forwards, metres
  double glyph_aside = 0.45;    ///< ... and sideways (towards the inside of the turn), metres
  bool stop_zone = false;
  StopZoneParameters stop;
  bool corridor = false;
  CorridorParameters corridor_parameters;
  /// The robot's footprint for the corridor: a radius (> 0), or else the polygon (robot frame).
  double corridor_radius = 0.3;
  std::vector<Vec2> corridor_footprint;
  /// The off-view cue (OffViewCue): drawn by the display from CueDrawing's robotArc() and
  /// horizonStart(); here only so that the robot is looked up for it.
  bool off_view = false;

  /// Whether any cue needs the robot's position (horizon, turn signal, stop zone, corridor, off-view).
  bool needsRobot() const { return horizon || turn_signal || stop_zone || corridor || off_view; }
};

/// The inputs that change over time.
struct PathCueInput
{
  double time = 0.0;          ///< seconds (ROS time)
  bool robot_known = false;   ///< the robot's position could be looked up
  Vec2 robot;                 ///< the robot's floor position in the path's (fixed) frame
  double heading = 0.0;       ///< the robot's heading (its x axis on the floor), radians
  GoalCueFrame goal;          ///< from GoalCueTimeline (default: draw everything, Normal colours)
  SpeedEstimate speed;        ///< the robot's filtered speed (default: standing) for the stop zone
};

/**
 * Builds the triangles for one instant.
 *
 * - Arrows: those of `spaced` (spaced with marchingPhase() when marching) that the goal frame shows
 *   and the horizon keeps: an arrow is kept when HorizonWindow::alpha(tip) > 0, with tip arc length
 *   from the start = path length - tip_from_end; its three triangles get that alpha per vertex.
 *   Without a known robot the horizon starts at the path's first point (the planner's path starts at
 *   the robot when it is planned).
 * - Destination: the circle (or, for a failed goal, a cross of the circle's diameter) when the goal
 *   frame shows it, with alpha(path length).
 * - Turn glyph: when the turn signal is on, the robot is known, detectTurn finds a turn and the
 *   arrows are shown, lit while blinkOn(time, turn_hz) (blinking from time 0, so every projector
 *   blinks in step).
 * - Corridor: when on and the goal frame shows the arrows, SweptCorridor from the robot's arc length
 *   (as the stop zone) over corridor_parameters.length, with the radius (> 0) or the footprint
 *   polygon; rebuilt only when the path, the robot's place on it or the settings changed.
 * - Stop zone: when on and the goal frame shows the arrows, StopZone::build from the robot's arc
 *   length (the path's start without a known robot, as the horizon) at `input.speed`; the horizon
 *   does not cut it.
 * `animating` says whether the result can change with time alone (marching, a blinking glyph, a
 * goal frame that animates): the display then keeps rendering frames.
 * Buffers are kept between calls (no allocation once big enough).
 */
class CueDrawing
{
public:
  void build(const std::vector<Vec2>& path, const SpacedPath& spaced, const SpacingParameters& parameters,
             const PathCueSettings& settings, const PathCueInput& input);

  /// Arrow triangles (ArrowOutline, 9 vertices per arrow) and one alpha factor per vertex (0..1).
  const std::vector<Vec2>& arrows() const { return arrows_; }
  const std::vector<float>& arrowAlpha() const { return arrow_alpha_; }
  std::size_t arrowsDrawn() const;
  /// Destination triangles (disc or cross; empty when not shown) and their alpha factor.
  const std::vector<Vec2>& destination() const { return destination_; }
  float destinationAlpha() const { return destination_alpha_; }
  bool cross() const { return cross_; }
  /// Turn-signal glyph triangles (empty when not shown) and what was detected.
  const std::vector<Vec2>& glyph() const { return glyph_; }
  const TurnDetection& turn() const { return turn_; }
  /// The stop zone's triangles and per-vertex alpha (not shown: empty).
  const StopZone& stopZone() const { return stop_zone_; }
  /// The swept corridor (not shown: empty).
  const SweptCorridor& corridor() const { return corridor_; }
  bool animating() const { return animating_; }
  /// Whether the horizon is limited (for the display's status): where it starts, arc length.
  double horizonStart() const { return horizon_start_; }
  /// The robot's place on the path (arc length; 0 without a known robot), as the horizon uses it.
  double robotArc() const { return robot_arc_; }
  /// Arc length at each path point (of the last build).
  const std::vector<double>& lengths() const { return lengths_; }

private:
  std::vector<double> lengths_;
  std::vector<Vec2> arrows_;
  std::vector<float> arrow_alpha_;
  std::vector<Vec2> destination_;
  std::vector<Vec2> glyph_;
  float destination_alpha_ = 1.0f;
  bool cross_ = false;
  bool animating_ = false;
  TurnDetection turn_;
  StopZone stop_zone_;
  SweptCorridor corridor_;
  /// What corridor_ was last built from: rebuilt only when one of these changes.
  struct CorridorKey
  {
    const Vec2* path = nullptr;
    std::size_t path_size = 0;
    Vec2 first, last;
    double robot_arc = -1.0;
    double radius = 0.0;
    std::vector<Vec2> footprint;
    CorridorParameters parameters;
    bool operator==(const CorridorKey& o) const;
  } corridor_key_;
  double horizon_start_ = 0.0;
  double robot_arc_ = 0.0;
};
}  // namespace rviz_projector
