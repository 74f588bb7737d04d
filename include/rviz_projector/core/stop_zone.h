// Stop zone cue of ProjectedPath (issue 25): a bar across the path where the robot would come to a
// stop at its current speed, the floor between the robot and the bar filled or hatched. Stopping
// distance, the speed filter that keeps odometry noise from moving the bar, and the zone's
// triangles along the path's curve (no ROS, no OGRE).
#pragma once

#include <vector>

#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/// Stopping distance d = v^2 / (2 a) + |v| t_react for a speed `speed` (m/s; its magnitude is used:
/// reverse motion counts like forward motion), a deceleration `deceleration` (m/s^2, > 0) and a
/// reaction time `reaction_time` (s, >= 0). NaN for non-finite input, a deceleration <= 0 or a
/// negative reaction time.
double stoppingDistance(double speed, double deceleration, double reaction_time);

/// The filtered speed at an instant and whether the robot counts as moving.
struct SpeedEstimate
{
  double speed = 0.0;   ///< filtered speed, m/s (>= 0)
  bool moving = false;  ///< false: the robot stands, no stop zone
};

/**
 * Smooths measured speeds (odometry) so that the stop zone moves smoothly and does not flicker.
 *
 * - A first-order low-pass with time constant kTimeConstant of the measured speed held between
 *   measurements: after a measurement u at t0 the output is y(t) = u + (y(t0) - u) exp(-(t - t0) / tau).
 *   Exact for any measurement rate (the output does not depend on how often it is read); a step
 *   reaches 63 % after tau and 99 % after 4.6 tau.
 * - The first measurement is taken as it is (no ramp from 0 when rviz starts beside a driving robot).
 * - Standing, with hysteresis: the robot counts as moving once the filtered speed exceeds kMoveAbove
 *   and as standing once it falls below kStandBelow, so noise around a few cm/s does not make the
 *   zone blink.
 * - A measurement earlier than the previous one (time went back) starts the filter afresh.
 */
class SpeedFilter
{
public:
  static constexpr double kTimeConstant = 0.3;  ///< seconds
  static constexpr double kStandBelow = 0.02;   ///< m/s
  static constexpr double kMoveAbove = 0.03;    ///< m/s

  /// A measured speed (m/s; its magnitude is used) at `time` (s). Non-finite input is ignored
  /// (the caller reports it).
  void add(double speed, double time);
  /// The filtered speed at `time` (>= the last measurement's time; earlier: its value then) and the
  /// moving/standing state (updated by this call). No measurement yet: standing, speed 0.
  SpeedEstimate at(double time);
  void clear();
  bool empty() const { return !has_value_; }
  /// The time of the last measurement (meaningless while empty()).
  double lastTime() const { return time_; }

private:
  double valueAt(double time) const;

  bool has_value_ = false;
  double value_ = 0.0;  // output at time_
  double input_ = 0.0;  // the held measurement
  double time_ = 0.0;
  bool moving_ = false;
};

/// How the stop zone is drawn (ProjectedPath's Stop zone properties).
struct StopZoneParameters
{
  double deceleration = 0.5;   ///< m/s^2
  double reaction_time = 0.3;  ///< s
  double width = 0.3;          ///< metres across the path
  bool hatched = false;        ///< stripes across the path instead of a filled area
  double fill_alpha = 0.4;     ///< opacity factor of the fill or stripes (the bar is opaque)
};

/// Geometry of the zone's parts along the path (metres).
constexpr double kStopBarThickness = 0.05;  ///< along the path; its far edge is the stopping point
constexpr double kStopStripeLength = 0.05;  ///< hatched: each stripe, along the path
constexpr double kStopStripePeriod = 0.15;  ///< hatched: from one stripe's start to the next, from the robot on
constexpr int kStopMaxStripes = 2000;       ///< hatched: beyond 300 m of stripes the rest is filled

/**
 * Appends the triangles of the strip of path between arc lengths `from` and `to` (clamped to
 * [0, path length]; nothing when to <= from), `width` metres across and centred on the path,
 * following its corners: at each path point inside the strip both edges turn by the mitre (the
 * offset along the bisector of the two segments' normals, at most twice half the width on very
 * sharp corners). `lengths` comes from accumulateArcLengths(points).
 */
void appendPathBand(const std::vector<Vec2>& points, const std::vector<double>& lengths, double from, double to,
                    double width, std::vector<Vec2>& out);

/// Working buffers of appendPathBand, kept between calls (no allocation once big enough).
struct PathBandScratch
{
  std::vector<Vec2> centre;
  std::vector<Vec2> offset;
};
/// The same with caller-owned working buffers.
void appendPathBand(const std::vector<Vec2>& points, const std::vector<double>& lengths, double from, double to,
                    double width, std::vector<Vec2>& out, PathBandScratch& scratch);

/**
 * The stop zone for a robot at arc length `robot_arc` of the path moving at the filtered speed
 * `speed` (SpeedEstimate; not moving: empty).
 *
 * The stopping point is at arc length end = min(robot_arc + stoppingDistance(...), path length):
 * never beyond the destination. Drawn: the bar, the strip [end - kStopBarThickness, end] (clipped at
 * the robot) with alpha factor 1, and before it, from the robot on, the fill (one strip) or the
 * stripes ([robot_arc + k kStopStripePeriod, + kStopStripeLength]) with alpha factor fill_alpha.
 * Empty for an empty or one-point path, a non-finite distance or a zone shorter than 1 mm.
 * Buffers are kept between calls (no allocation once big enough).
 */
class StopZone
{
public:
  void build(const std::vector<Vec2>& points, const std::vector<double>& lengths, double robot_arc,
             const SpeedEstimate& speed, const StopZoneParameters& parameters);

  /// Triangles (fill first, then the bar) and one alpha factor per vertex.
  const std::vector<Vec2>& triangles() const { return triangles_; }
  const std::vector<float>& alpha() const { return alpha_; }
  bool shown() const { return !triangles_.empty(); }
  /// Arc lengths of the zone: from the robot to the stopping point (0, 0 when not shown).
  double start() const { return start_; }
  double end() const { return end_; }

private:
  std::vector<Vec2> triangles_;
  std::vector<float> alpha_;
  PathBandScratch scratch_;
  double start_ = 0.0;
  double end_ = 0.0;
};
}  // namespace rviz_projector
