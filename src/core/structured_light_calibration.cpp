#include "rviz_projector/core/structured_light_calibration.h"

#include <cstdio>
#include <string>

#include "rviz_projector/core/camera_floor.h"

namespace rviz_projector
{
namespace
{
/// "12.3 %"
std::string percent(double fraction)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f %%", 100.0 * fraction);
  return text;
}
}  // namespace

CameraCalibrationResult solveFromCaptures(const CameraCalibrationInput& input, const std::vector<cv::Mat>& captures)
{
  CameraCalibrationResult result;
  const CameraCalibrationLimits& limits = input.limits;
  const int w = static_cast<int>(input.lens.width());
  const int h = static_cast<int>(input.lens.height());
  result.decoded = decodeGrayCode(w, h, captures);
  const GrayDecodeResult& decoded = result.decoded;
  if (!decoded.error.empty())
  {
    result.error = "the captured frames cannot be decoded: " + decoded.error;
    return result;
  }
  const double camera_pixels = captures.empty() ? 1.0 : double(captures[0].total());
  if (decoded.lit < limits.min_lit * camera_pixels)
  {
    result.error = "the camera sees too little of the projection: " + percent(decoded.lit / camera_pixels) +
                   " of its pixels are lit by the white frame (at least " + percent(limits.min_lit) +
                   " needed): point the camera at the lit floor, or check --image";
    return result;
  }
  if (decoded.saturated > limits.max_saturated * decoded.lit)
  {
    result.error = "the patterns saturate the camera: " + percent(double(decoded.saturated) / decoded.lit) +
                   " of the lit pixels are white in the white frame (at most " + percent(limits.max_saturated) +
                   "): lower the camera's exposure or gain";
    return result;
  }
  if (decoded.decoded < limits.min_decoded * decoded.lit)
  {
    result.error = "the patterns cannot be decoded: only " + percent(double(decoded.decoded) / decoded.lit) +
                   " of the lit camera pixels gave a projector pixel (at least " + percent(limits.min_decoded) +
                   "): too little contrast (ambient light, focus), or frames captured before their pattern was "
                   "on the floor (raise --settle)";
    return result;
  }
  const Correspondences found = floorCorrespondences(decoded, input.camera, input.floor_T_camera, w, h);
  if (!found.error.empty())
  {
    result.error = found.error;
    return result;
  }
  result.correspondences = found.points.size();
  result.coverage = found.coverage;
  if (found.coverage < limits.min_coverage)
  {
    result.error = "the camera sees only " + percent(found.coverage) + " of the projector's image on the floor (at least " +
                   percent(limits.min_coverage) + " needed for a sound solve): move the camera or the robot";
    return result;
  }
  DenseSolveOptions options;
  options.fit_distortion = input.fit_distortion;
  options.distortion = input.distortion;
  result.solution = solveMountDense(input.lens, found.points, input.prior, options);
  if (!result.solution.ok)
  {
    result.error = "no solution: " + result.solution.error;
  }
  return result;
}

}  // namespace rviz_projector
