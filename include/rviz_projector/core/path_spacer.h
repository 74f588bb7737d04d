// Places arrows along a path: the spacing core of rviz_projector (no ROS, no OGRE).
#pragma once

#include <vector>

#include "rviz_projector/core/spaced_path.h"
#include "rviz_projector/core/spacing_parameters.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
/**
 * Turns a path (planar positions ordered start -> destination, unevenly spaced) into arrows.
 *
 * Exact mode: tip k lies at arc length  r + gap + k * spacing  back from the destination
 * (r = circle radius), its tail  shaft_length + head_length  further back; the arrow is the chord
 * tail -> tip. Arc lengths are summed from the destination, so trimming the start of the path
 * (the robot advancing along the same plan) leaves every remaining arrow bit-for-bit where it was.
 * With SpacingParameters::speed_coding enabled, tip k+1 lies speedCodedSpacing(tip k) beyond tip k
 * instead (speed_spacing.h), still counted from the destination.
 *
 * Paper mode: Algorithm 1 of the paper, as the reference code runs it: keep the destination; from
 * the last kept pose walk back to the first pose at least `spacing` away in (x, y)
 * (`spacing + circle_diameter` from the destination) and keep it; stop when the walk runs off the
 * start of the path or reaches its first pose (index 0 is never kept, as in the reference loop
 * `while (curr_i > 0)`). Arrows join kept points pairwise: tail = kept[2k+1], tip = kept[2k].
 *
 * Points with a NaN/Inf coordinate are dropped and counted. Runs in O(n + arrows), no recursion.
 * The object keeps its buffers between calls: reuse one instance to avoid allocations.
 */
class PathSpacer
{
public:
  explicit PathSpacer(const SpacingParameters& parameters = SpacingParameters());

  void setParameters(const SpacingParameters& parameters);
  const SpacingParameters& parameters() const { return parameters_; }

  /// Computes the arrows; the returned reference stays valid until the next call.
  /// `phase` (Exact mode only; metres, in [0, spacing), see marching.h): every tip lies `phase`
  /// further from the destination, tip k at  r + gap + phase + k * spacing. 0 (the default) is the
  /// static layout; values outside [0, spacing) or NaN are wrapped into it (NaN: 0). Paper mode
  /// ignores it.
  const SpacedPath& space(const std::vector<Vec2>& path, double phase = 0.0);

private:
  void accumulateFromEnd(const std::vector<Vec2>& points);  // fills from_end_
  void placeExact();
  void placePaper();

  SpacingParameters parameters_;
  std::vector<Vec2> points_;                            // finite input points, when some were not
  const std::vector<Vec2>* points_in_use_ = &points_;   // during space(): the input, or points_
  std::vector<double> from_end_;                        // arc length from the destination to each point
  std::vector<Vec2> kept_;    // Paper mode scratch
  std::vector<double> kept_from_end_;  // arc length from the destination of each kept point
  double phase_ = 0.0;        // Exact mode: marching phase of this call, in [0, spacing)
  SpacedPath result_;
};
}  // namespace rviz_projector
