// Verdict on a LensCalibration: an error makes it unusable, a warning is worth telling the user.
#pragma once

#include <string>

namespace rviz_projector
{
struct LensCheck
{
  /// Empty when the calibration is usable.
  std::string error;
  /// Non-fatal remarks (e.g. distortion that is not applied); empty when none.
  std::string warning;

  bool ok() const { return error.empty(); }
};
}  // namespace rviz_projector
