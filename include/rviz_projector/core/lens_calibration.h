// The numbers of a sensor_msgs/CameraInfo that describe a projector's lens, without ROS types.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace rviz_projector
{
struct LensCalibration
{
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::string distortion_model;
  std::vector<double> D;
  std::array<double, 9> K{};
  std::array<double, 12> P{};
  std::uint32_t binning_x = 0;
  std::uint32_t binning_y = 0;
  std::uint32_t roi_x_offset = 0;
  std::uint32_t roi_y_offset = 0;
  std::uint32_t roi_width = 0;
  std::uint32_t roi_height = 0;
};

/// Whether two calibrations describe the same lens: every field above, value for value (a
/// CameraInfo republished with every camera frame is the same lens; only a changed value is news).
/// NaN never equals itself, so a calibration holding NaN is "changed" each time - and refused by
/// PinholeModel::fromCalibration anyway.
bool sameLens(const LensCalibration& a, const LensCalibration& b);
}  // namespace rviz_projector
