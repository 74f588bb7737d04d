// The four arrow sizes rviz's own arrow uses, in metres.
#pragma once

namespace rviz_projector
{
struct ArrowDimensions
{
  double shaft_length = 0.10;
  double shaft_diameter = 0.05;
  double head_length = 0.08;
  double head_diameter = 0.12;

  /// Tail-to-tip length of an arrow placed along the path in Exact mode.
  double length() const { return shaft_length + head_length; }
};
}  // namespace rviz_projector
