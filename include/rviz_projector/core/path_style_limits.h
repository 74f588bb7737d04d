// Limits and defaults of the path style, shared by the ProjectedPath display (its properties) and
// the path_to_markers node (its parameters), so that both accept exactly the same values. The
// spacing, arrow and circle defaults are SpacingParameters' own (spacing_parameters.h).
#pragma once

namespace rviz_projector
{
namespace path_style
{
/**
 * Smallest spacing, metres. 1 cm: below it arrows (at least kMinSize long) overlap into a solid
 * band and a long path needs millions of them. PathSpacer raises smaller values to it too
 * (SpacingParameters::kMinSpacing), so the display, the node and the spacer agree.
 */
constexpr double kMinSpacing = 0.01;
/// Largest spacing, metres: one arrow per 100 m is no path to follow any more.
constexpr double kMaxSpacing = 100.0;
/// Smallest arrow size or circle diameter, metres: a zero-sized shape would silently vanish.
constexpr double kMinSize = 0.005;
/// Largest arrow size or circle diameter, metres: beyond a few metres arrows stop meaning anything.
constexpr double kMaxSize = 10.0;
/// Height of the drawing above z = 0 of the fixed frame, metres: kept within +-kMaxHeight.
constexpr double kMaxHeight = 10.0;
/// Default height: a little lift avoids fighting with a grid or map on the floor.
constexpr double kDefaultHeight = 0.01;
/**
 * Largest floor coordinate drawn, metres (a trillion: far beyond any map, yet its arrows still
 * fit OGRE's single-precision vertices and bounding boxes). Poses beyond it count as unusable,
 * like NaN/Inf ones.
 */
constexpr double kMaxFloorCoordinate = 1e12;
/// Default opacity (1 opaque).
constexpr double kDefaultAlpha = 1.0;
}  // namespace path_style
}  // namespace rviz_projector
