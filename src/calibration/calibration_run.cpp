#include "rviz_projector/calibration/calibration_run.h"

#include <array>
#include <sstream>
#include <vector>

#include <camera_calibration_parsers/parse_yml.h>

#include "rviz_projector/calibration/calibration_report.h"
#include "rviz_projector/calibration/mount_file.h"
#include "rviz_projector/calibration/number_format.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
std::string templateHeader(const CalibrateOptions& options, const CalibrationInput& input)
{
  std::ostringstream text;
  text << "# rviz_projector calibration points: the " << options.rows << "x" << options.cols
       << " crosshair pattern of a " << input.lens.width() << "x" << input.lens.height() << " projector\n"
       << "# (" << input.file.path << ", '" << input.file.camera_name << "').\n"
       << "# Show it with the ProjectorCamera's Test pattern: Crosshairs (same rows and columns), mark each\n"
       << "# crosshair's centre on the floor and measure it in '" << options.frame
       << "' (metres: x forward, y left, z = 0 the floor).\n"
       << "# Replace 'x: null, y: null' by the numbers; add 'z: 0.4' for a crosshair on a box 0.4 m high.\n"
       << "# Delete the lines of crosshairs you could not measure (at least 4 points; 6 or more spread over\n"
       << "# the image are better). u, v are the projector pixels; they may be left out (taken by id).\n"
       << "# Then: rosrun rviz_projector calibrate_projector --camera-info " << options.camera_info
       << " --points points.yaml --output mount.yaml";
  if (options.rows != CrosshairPatternSize::kDefaultRows || options.cols != CrosshairPatternSize::kDefaultCols)
  {
    text << " --rows " << options.rows << " --cols " << options.cols;
  }
  text << "\n";
  return text.str();
}

std::string mountHeader(const CalibrateOptions& options, const std::string& points_name)
{
  return "# Projector mount solved by calibrate_projector from " + points_name + " and " + options.camera_info +
         ".\n# roslaunch rviz_projector projector.launch mount_file:=<this file> (wins over x/y/z/roll/pitch/yaw)\n";
}
}  // namespace

int reportError(std::ostream& err, const std::string& message)
{
  err << "calibrate_projector: error: " << message << "\n";
  return kExitBadInput;
}

int loadCalibrationInput(const CalibrateOptions& options, CalibrationInput& out, std::ostream& err)
{
  out = CalibrationInput();
  // loadCalibrationFile checks the lens with PinholeModel::fromCalibration, as the display does.
  const std::string error = loadCalibrationFile(options.camera_info, out.file);
  if (!error.empty())
  {
    return reportError(err, error);
  }
  for (const std::string& warning : out.file.warnings)
  {
    err << "calibrate_projector: warning: " << out.file.path << ": " << warning << "\n";
  }
  const LensCheck check = PinholeModel::fromCalibration(toLensCalibration(out.file.info), out.lens);
  if (!check.ok())
  {
    return reportError(err, out.file.path + ": unusable calibration: " + check.error);
  }
  out.pattern = crosshairPattern(out.lens.width(), out.lens.height(), options.rows, options.cols);
  if (out.pattern.empty())
  {
    return reportError(err, "no crosshair pattern for " + out.file.path + ": " +
                                crosshairPatternProblem(out.lens.width(), out.lens.height(), options.rows,
                                                        options.cols));
  }
  out.pattern_name = "the " + std::to_string(options.rows) + "x" + std::to_string(options.cols) + " pattern";
  return kExitOk;
}

int runPattern(const CalibrateOptions& options, std::ostream& out, std::ostream& err)
{
  CalibrationInput input;
  const int status = loadCalibrationInput(options, input, err);
  if (status != kExitOk)
  {
    return status;
  }
  out << calibrationPointsTemplate(input.pattern, options.frame, templateHeader(options, input));
  return kExitOk;
}

int runSolve(const CalibrateOptions& options, std::ostream& out, std::ostream& err)
{
  CalibrationInput input;
  const int status = loadCalibrationInput(options, input, err);
  if (status != kExitOk)
  {
    return status;
  }
  CalibrationPoints points;
  const std::string error = readCalibrationPoints(options.points, input.pattern, input.pattern_name, points);
  if (!error.empty())
  {
    return reportError(err, error);
  }
  return solveAndWrite(options, input, points, options.points, out, err);
}

int solveAndWrite(const CalibrateOptions& options, const CalibrationInput& input, const CalibrationPoints& points,
                  const std::string& points_name, std::ostream& out, std::ostream& err)
{
  const std::string problem = floorPointsProblem(input.lens, points.points);
  if (!problem.empty())
  {
    return reportError(err, points_name + ": " + problem);
  }
  MountSolverOptions solver_options = MountSolverOptions::forTapeError(options.tape_error);
  solver_options.fit_intrinsics = options.fit_intrinsics;
  solver_options.fit_distortion = options.fit_distortion;
  const MountSolution solution = solveMount(input.lens, points.points, solver_options);
  if (!solution.ok)
  {
    return reportError(err, points_name + ": no solution: " + solution.error);
  }
  // solveMount never returns ok with a non-finite mount (checked there, for every caller).
  // Everything to write is composed first: a failure leaves no half-written set of files.
  std::string calibration_text;
  if (!options.output_calibration.empty())
  {
    std::ostringstream yaml;
    sensor_msgs::CameraInfo fitted = fittedCameraInfo(input.file.info, solution.lens);
    if (options.fit_distortion)
    {
      // plumb_bob D = [k1, k2, 0, 0, 0]: D is on normalised coordinates, binning and ROI leave it alone.
      const std::vector<double> d = solution.distortion.none() ? std::vector<double>(5, 0.0)
                                                               : solution.distortion.coefficients();
      fitted.distortion_model = "plumb_bob";
      fitted.D = {d[0], d[1], 0.0, 0.0, 0.0};
    }
    if (!camera_calibration_parsers::writeCalibrationYml(yaml, input.file.camera_name, fitted))
    {
      return reportError(err, options.output_calibration + ": the fitted calibration could not be formatted");
    }
    calibration_text = yaml.str();
  }
  std::vector<std::pair<std::string, std::string>> files;
  if (!options.output.empty())
  {
    files.emplace_back(options.output, mountFileYaml(points.frame, solution, mountHeader(options, points_name)));
  }
  if (!options.output_calibration.empty())
  {
    files.emplace_back(options.output_calibration, calibration_text);
  }
  if (const std::string error = writeTextFiles(files); !error.empty())
  {
    return reportError(err, error + " (no file written)");
  }

  out << solutionReport(points.frame, solution, options.output);
  if (options.fit_intrinsics)
  {
    const PinholeModel& fitted = solution.lens;
    const std::array<double, 4>& sigma = solution.lens_stddev;
    out << "Fitted intrinsics (1 sigma): fx " << fixedDecimals(fitted.fx(), 1) << " +- " << fixedDecimals(sigma[0], 1)
        << ", fy " << fixedDecimals(fitted.fy(), 1) << " +- " << fixedDecimals(sigma[1], 1) << ", cx "
        << fixedDecimals(fitted.cx(), 1) << " +- " << fixedDecimals(sigma[2], 1) << ", cy "
        << fixedDecimals(fitted.cy(), 1) << " +- " << fixedDecimals(sigma[3], 1) << " px (were fx "
        << input.lens.fx() << ", fy " << input.lens.fy() << ", cx " << input.lens.cx() << ", cy " << input.lens.cy()
        << ")\n";
    if (!options.output_calibration.empty())
    {
      out << "  written to " << options.output_calibration << ": use it as calibration_file:=\n";
    }
  }
  if (options.fit_distortion)
  {
    const std::vector<double> d =
        solution.distortion.none() ? std::vector<double>(5, 0.0) : solution.distortion.coefficients();
    out << "Fitted distortion (plumb_bob, 1 sigma): k1 " << fixedDecimals(d[0], 5) << " +- "
        << fixedDecimals(solution.distortion_stddev[0], 5) << ", k2 " << fixedDecimals(d[1], 5) << " +- "
        << fixedDecimals(solution.distortion_stddev[1], 5) << " (the calibration's D is not used by the solver)\n";
    if (!options.output_calibration.empty())
    {
      out << "  written to " << options.output_calibration << " as D = [k1, k2, 0, 0, 0]: use it as "
          << "calibration_file:=\n";
    }
  }
  return kExitOk;
}
}  // namespace rviz_projector
