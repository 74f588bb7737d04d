// The modes of calibrate_projector (issue 12) that need no ROS master: --pattern and solving from
// a points file; and the solve-and-write step the --clicked-points mode shares. Each returns the
// process's exit status (CalibrateExit) and prints the result on `out`, problems on `err`.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "rviz_projector/calibration/calibrate_projector_options.h"
#include "rviz_projector/calibration/calibration_file.h"
#include "rviz_projector/calibration/calibration_points_file.h"
#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/pinhole_model.h"

namespace rviz_projector
{
/// The calibration of --camera-info, checked as the display checks it, and its crosshair pattern.
struct CalibrationInput
{
  CalibrationFile file;
  PinholeModel lens;
  std::vector<Crosshair> pattern;
  std::string pattern_name;  ///< e.g. "the 3x3 pattern"
};

/// Loads --camera-info and makes the pattern; kExitOk or kExitBadInput (message on `err`).
int loadCalibrationInput(const CalibrateOptions& options, CalibrationInput& out, std::ostream& err);

/// --pattern: prints the points template.
int runPattern(const CalibrateOptions& options, std::ostream& out, std::ostream& err);

/// --points: reads the points file and solves (solveAndWrite).
int runSolve(const CalibrateOptions& options, std::ostream& out, std::ostream& err);

/// Checks the points, solves, writes --output (and --output-calibration) and prints the report.
/// `points_name` names the points' origin in messages (the points file).
int solveAndWrite(const CalibrateOptions& options, const CalibrationInput& input, const CalibrationPoints& points,
                  const std::string& points_name, std::ostream& out, std::ostream& err);

/// "calibrate_projector: error: " + message, on `err`; returns kExitBadInput.
int reportError(std::ostream& err, const std::string& message);
}  // namespace rviz_projector
