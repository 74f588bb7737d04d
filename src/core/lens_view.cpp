#include "rviz_projector/core/lens_view.h"

#include <cmath>
#include <cstdio>

namespace rviz_projector
{
PinholeModel scaledLens(const PinholeModel& lens, std::uint32_t width, std::uint32_t height)
{
  if (lens.width() == 0 || lens.height() == 0)
  {
    return lens;
  }
  const double sx = static_cast<double>(width) / lens.width();
  const double sy = static_cast<double>(height) / lens.height();
  return PinholeModel(width, height, lens.fx() * sx, lens.fy() * sy, (lens.cx() + 0.5) * sx - 0.5,
                      (lens.cy() + 0.5) * sy - 0.5, lens.tx() * sx, lens.ty() * sy);
}

std::string narrowViewWarning(const PinholeModel& lens)
{
  const double fov_x = 2.0 * std::atan(0.5 * lens.width() / std::abs(lens.fx()));
  const double fov_y = 2.0 * std::atan(0.5 * lens.height() / std::abs(lens.fy()));
  if (fov_x >= kMinFieldOfView && fov_y >= kMinFieldOfView)
  {
    return std::string();
  }
  constexpr double kDegrees = 180.0 / 3.14159265358979323846;
  char text[256];
  std::snprintf(text, sizeof text,
                "Field of view %.3g x %.3g degrees (fx %.6g, fy %.6g): so narrow that the projector shows "
                "practically nothing; check the CameraInfo's focal lengths (pixels)",
                fov_x * kDegrees, fov_y * kDegrees, lens.fx(), lens.fy());
  return text;
}
}  // namespace rviz_projector
