#include "rviz_projector/core/lens_calibration.h"

namespace rviz_projector
{
bool sameLens(const LensCalibration& a, const LensCalibration& b)
{
  return a.width == b.width && a.height == b.height && a.distortion_model == b.distortion_model && a.D == b.D &&
         a.K == b.K && a.P == b.P && a.binning_x == b.binning_x && a.binning_y == b.binning_y &&
         a.roi_x_offset == b.roi_x_offset && a.roi_y_offset == b.roi_y_offset && a.roi_width == b.roi_width &&
         a.roi_height == b.roi_height;
}
}  // namespace rviz_projector
