// Command line of calibrate_projector (issue 12).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rviz_projector/core/board_view.h"
#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"

namespace rviz_projector
{
/// Exit statuses of calibrate_projector.
enum CalibrateExit
{
  kExitOk = 0,
  kExitBadInput = 1,  ///< bad input or no solution: a message on stderr, nothing written
  kExitUsage = 2,     ///< bad command line
};

struct CalibrateOptions
{
  enum class Mode
  {
    Help,
    Pattern,
    Solve,
    ClickedPoints,
    Camera,  ///< --camera: structured light through the projector, seen by the robot's camera
  };
  Mode mode = Mode::Solve;
  std::string camera_info;         ///< --camera-info: calibration YAML (path, package://, file://)
  std::string points;              ///< --points: points.yaml to solve from
  std::string output;              ///< --output: mount.yaml to write ("" = none)
  std::string output_calibration;  ///< --output-calibration: the fitted calibration (--fit-intrinsics/-distortion)
  std::string points_out;          ///< --points-out: points.yaml the clicked points are written to
  std::string frame = "base_link";  ///< --frame: frame of the template / the clicked points
  int rows = CrosshairPatternSize::kDefaultRows;
  int cols = CrosshairPatternSize::kDefaultCols;
  bool fit_intrinsics = false;
  /// --fit-distortion: also fit k1, k2 (written as plumb_bob D = [k1, k2, 0, 0, 0]).
  bool fit_distortion = false;
  /// --tape-error MM: how accurately the points were measured (1 sigma), metres.
  double tape_error = MountSolverOptions().tape_error;
  // --camera (issue 24):
  std::string image = "/camera/image_raw";          ///< --image: the camera's image (CameraInfo beside it)
  std::string pattern_topic = "/projector/pattern";  ///< --pattern-topic: the ProjectorCamera's Pattern topic
  std::string floor_frame;                           ///< --floor-frame: z = 0 of it is the floor ("" = --frame)
  std::string projector_frame = "projector_optical_frame";  ///< --projector-frame: the current mount (a prior)
  double settle = 0.15;  ///< --settle SECONDS after the projector acknowledged a pattern, before a frame counts
  bool keep_distortion = false;  ///< --keep-distortion: --camera keeps the file's D instead of fitting k1, k2
  /// --board COLSxROWS:SQUARE_M: --camera also fits fx, fy, cx, cy with a checkerboard tilted on the floor.
  std::optional<BoardSpec> board;
};

/// Parses the arguments (without the program name). Returns "" or what is wrong with them.
std::string parseCalibrateOptions(const std::vector<std::string>& args, CalibrateOptions& out);

/// The --help text.
std::string calibrateUsage();
}  // namespace rviz_projector
