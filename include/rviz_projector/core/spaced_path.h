// Output of PathSpacer: arrows on the floor and the destination.
#pragma once

#include <cstddef>
#include <vector>

#include "rviz_projector/core/arrow.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
struct SpacedPath
{
  /// Ordered from the destination backwards (arrow 0 is the one nearest the destination).
  std::vector<Arrow> arrows;
  /// Arc length from the destination to each arrow's tip along the path (same order as `arrows`):
  /// what the horizon cue judges an arrow by (arc length from the start = path_length - this).
  std::vector<double> tip_from_end;
  bool has_destination = false;
  Vec2 destination;
  /// Input points dropped because a coordinate was NaN or infinite.
  std::size_t dropped_points = 0;
  /// True when SpacingParameters::max_arrows cut the list short.
  bool truncated = false;
  /// Planar length of the (finite part of the) path, metres.
  double path_length = 0.0;
};
}  // namespace rviz_projector
