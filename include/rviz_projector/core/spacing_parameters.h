// Inputs of PathSpacer besides the path itself.
#pragma once

#include <cstddef>

#include "rviz_projector/core/arrow_dimensions.h"
#include "rviz_projector/core/path_style_limits.h"
#include "rviz_projector/core/spacing_mode.h"
#include "rviz_projector/core/speed_spacing.h"

namespace rviz_projector
{
struct SpacingParameters
{
  SpacingMode mode = SpacingMode::Exact;
  /// Exact: arc length tip to tip. Paper: minimum planar distance between kept points (D).
  double spacing = 0.25;
  ArrowDimensions arrow;
  double circle_diameter = 0.20;
  /// Exact mode: free floor between the destination circle's edge and the first arrow's tip.
  double destination_gap = 0.05;
  /// Upper bound on the arrows produced (a 1e9 m path at 1 cm spacing must not allocate forever).
  std::size_t max_arrows = 100000;
  /// Exact mode: when enabled, tip k+1 lies speedCodedSpacing(tip k's distance from the
  /// destination) beyond tip k instead of `spacing` (the marching phase is then not applied).
  SpeedCoding speed_coding;

  /// Smallest spacing accepted; smaller values are raised to it. The same limit as the display's
  /// and path_to_markers' (path_style_limits.h).
  static constexpr double kMinSpacing = path_style::kMinSpacing;
};
}  // namespace rviz_projector
