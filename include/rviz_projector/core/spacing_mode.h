#pragma once

namespace rviz_projector
{
/// How arrows are placed along a path.
enum class SpacingMode
{
  /// Evenly by arc length, anchored at the destination (stable while the robot drives).
  Exact = 0,
  /// Point selection of Algorithm 1 of Han et al., HRI 2022, as in the published reference code.
  Paper = 1,
};
}  // namespace rviz_projector
