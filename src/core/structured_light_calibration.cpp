#include "rviz_projector/core/structured_light_calibration.h"

#include <cstdio>
#include <string>

#include <opencv2/core.hpp>

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
  if (input.board)
  {
    result.board = findBoard(captures[0], input.camera, input.floor_T_camera, *input.board);
    if (!result.board.error.empty())
    {
      result.error = result.board.error;
      return result;
    }
  }
  // Without a board every decoded pixel is on the floor; with one, those near it are not.
  cv::Mat away_from_board;
  if (input.board)
  {
    cv::bitwise_not(result.board.near_board, away_from_board);
  }
  const Correspondences found =
      input.board ? floorCorrespondences(restrictDecode(decoded, away_from_board), input.camera, input.floor_T_camera, w, h)
                  : floorCorrespondences(decoded, input.camera, input.floor_T_camera, w, h);
  if (!found.error.empty())
  {
    result.error = found.error;
    return result;
  }
  result.correspondences = found.points.size();
  result.coverage = found.coverage;
  Correspondences on_board;
  if (input.board)
  {
    CorrespondenceOptions board_options;
    board_options.plane = result.board.plane;
    on_board = floorCorrespondences(restrictDecode(decoded, result.board.on_board), input.camera,
                                    input.floor_T_camera, w, h, board_options);
    if (!on_board.error.empty())
    {
      result.error = on_board.error;
      return result;
    }
    result.board_correspondences = on_board.points.size();
    result.coverage += on_board.coverage;  // the board hides part of the floor from the camera
    if (on_board.points.size() < std::size_t(limits.min_board_points))
    {
      result.error = "the camera sees only " + std::to_string(on_board.points.size()) +
                     " decoded projector cells on the checkerboard (at least " +
                     std::to_string(limits.min_board_points) + " needed): put it where the projector lights it, "
                     "nearer the camera, or use a larger board";
      return result;
    }
  }
  if (result.coverage < limits.min_coverage)
  {
    result.error = "the camera sees only " + percent(result.coverage) + " of the projector's image on the floor (at least " +
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
    return result;
  }
  if (input.board)
  {
    TwoPlaneLensOptions lens_options;
    lens_options.fit_distortion = input.fit_distortion;
    lens_options.min_board_points = limits.min_board_points;
    result.lens_fit = fitLensOnTwoPlanes(input.lens, result.solution.distortion, result.solution.parent_T_optical,
                                         found.points, on_board.points, lens_options);
    if (!result.lens_fit.ok)
    {
      result.error = "no lens from the board: " + result.lens_fit.error;
      return result;
    }
    result.lens_fitted = true;
  }
  return result;
}

}  // namespace rviz_projector
