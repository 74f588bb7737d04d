// What a lens shows: the lens of a scaled copy of the image (the letterboxed output window, the
// published Image), and a warning when the view is so narrow that it shows practically nothing.
#pragma once

#include <cstdint>
#include <string>

#include "rviz_projector/core/pinhole_model.h"

namespace rviz_projector
{
/**
 * The pinhole of the same view resampled to width x height pixels (each axis scaled by
 * width / lens.width(), height / lens.height()). Pixel centres stay at integers:
 * u' = (u + 0.5) * s - 0.5, so cx' = (cx + 0.5) * s - 0.5; fx and Tx scale by s.
 */
PinholeModel scaledLens(const PinholeModel& lens, std::uint32_t width, std::uint32_t height);

/// Narrowest useful view, radians (0.06 degrees: 1 mm at 1 m): below it the image is all but empty.
constexpr double kMinFieldOfView = 1e-3;
/// Empty when the view is usable; else a sentence for the user (field of view, focal lengths).
std::string narrowViewWarning(const PinholeModel& lens);
}  // namespace rviz_projector
