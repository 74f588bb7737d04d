#include "rviz_projector/calibration/camera_calibration.h"

#include <array>
#include <chrono>
#include <cmath>
#include <sstream>

#include <camera_calibration_parsers/parse_yml.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "rviz_projector/calibration/calibration_points_file.h"
#include "rviz_projector/calibration/calibration_report.h"
#include "rviz_projector/calibration/calibration_run.h"
#include "rviz_projector/calibration/mount_file.h"
#include "rviz_projector/calibration/number_format.h"
#include "rviz_projector/calibration/pattern_capture.h"
#include "rviz_projector/core/structured_light_calibration.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
std::string percent(double fraction)
{
  return fixedDecimals(100.0 * fraction, 1) + " %";
}

/// `frame`'s pose in `target` (latest), or "" with the error in `error`.
bool lookup(const tf2_ros::Buffer& tf, const std::string& target, const std::string& frame, double timeout,
            RigidTransform& out, std::string& error)
{
  try
  {
    out = toRigidTransform(tf.lookupTransform(target, frame, ros::Time(0), ros::Duration(timeout)).transform);
    return true;
  }
  catch (const tf2::TransformException& e)
  {
    error = e.what();
    return false;
  }
}

/// The calibration file's CameraInfo with the fitted distortion: plumb_bob k1 k2 0 0 0, P = [K | 0]
/// (with a distortion the projector draws through K).
sensor_msgs::CameraInfo withDistortion(sensor_msgs::CameraInfo info, const LensDistortion& distortion)
{
  info.distortion_model = "plumb_bob";
  info.D.assign(5, 0.0);
  const std::vector<double>& d = distortion.coefficients();
  for (std::size_t i = 0; i < d.size() && i < 5; ++i)
  {
    info.D[i] = d[i];
  }
  info.P = {info.K[0], info.K[1], info.K[2], 0.0, info.K[3], info.K[4], info.K[5], 0.0, info.K[6], info.K[7], info.K[8], 0.0};
  return info;
}

/// The calibration file's CameraInfo with the fitted lens: K, and P = [K | 0].
sensor_msgs::CameraInfo withLens(sensor_msgs::CameraInfo info, const PinholeModel& lens)
{
  info.K = {lens.fx(), 0.0, lens.cx(), 0.0, lens.fy(), lens.cy(), 0.0, 0.0, 1.0};
  info.P = {lens.fx(), 0.0, lens.cx(), 0.0, 0.0, lens.fy(), lens.cy(), 0.0, 0.0, 0.0, 1.0, 0.0};
  return info;
}

/// Seconds of the run: all, showing and capturing the patterns, decoding and solving.
struct Timing
{
  double total = 0.0;
  double capture = 0.0;
  double solve = 0.0;
  std::size_t patterns = 0;
};

/// The board's lines of the report: the fitted lens against the file's, and its residuals.
std::string lensReport(const CameraCalibrationResult& r, const PinholeModel& prior)
{
  const TwoPlaneLensFit& f = r.lens_fit;
  std::ostringstream text;
  text << "Board: tilted " << fixedDecimals(r.board.tilt_deg, 1) << " deg from the floor, "
       << fixedDecimals(r.board.distance, 2) << " m from the camera (corners RMS "
       << fixedDecimals(r.board.corner_rms_px, 2) << " px); " << r.board_correspondences << " correspondences on it\n";
  const double fitted[] = {f.lens.fx(), f.lens.fy(), f.lens.cx(), f.lens.cy()};
  const double file[] = {prior.fx(), prior.fy(), prior.cx(), prior.cy()};
  const char* names[] = {"fx", "fy", "cx", "cy"};
  text << "Lens (fitted, 1 sigma; the file's):";
  for (int k = 0; k < 4; ++k)
  {
    text << " " << names[k] << " " << fixedDecimals(fitted[k], 2) << " +- " << fixedDecimals(f.lens_stddev[std::size_t(k)], 2)
         << " (" << fixedDecimals(file[k], 2) << ")" << (k < 3 ? ";" : "");
  }
  text << "\n  (the 1 sigma assumes independent pixel errors; expect a few times more)\n";
  text << "Residuals: " << f.floor_inliers << " floor and " << f.board_inliers << " board inliers, " << f.outliers
       << " outliers; RMS " << fixedDecimals(f.rms_px, 3) << " px (board " << fixedDecimals(f.board_rms_px, 3)
       << " px); on the floor median " << fixedDecimals(f.floor_median_mm, 2) << " mm, max "
       << fixedDecimals(f.floor_max_mm, 2) << " mm\n";
  return text.str();
}

std::string report(const CameraCalibrationResult& r, const ProjectorMount& mount, const std::string& parent,
                   const ProjectorMount* prior, const Timing& timing, std::size_t camera_pixels,
                   const PinholeModel& file_lens)
{
  const DenseMountSolution& s = r.solution;
  std::ostringstream text;
  text << "Mount (projector.launch): " << launchArguments(parent, mount) << "\n";
  if (prior != nullptr)
  {
    const double moved = std::sqrt((mount.x - prior->x) * (mount.x - prior->x) +
                                   (mount.y - prior->y) * (mount.y - prior->y) +
                                   (mount.z - prior->z) * (mount.z - prior->z));
    text << "  moved from the current mount by " << fixedDecimals(moved * 1000.0, 1) << " mm; roll "
         << fixedDecimals((mount.roll - prior->roll) * 180.0 / M_PI, 3) << " deg, pitch "
         << fixedDecimals((mount.pitch - prior->pitch) * 180.0 / M_PI, 3) << " deg, yaw "
         << fixedDecimals((mount.yaw - prior->yaw) * 180.0 / M_PI, 3) << " deg\n";
  }
  const std::vector<double>& d = r.lens_fitted ? r.lens_fit.distortion.coefficients() : s.distortion.coefficients();
  const std::array<double, 2>& k_stddev = r.lens_fitted ? r.lens_fit.k_stddev : s.k_stddev;
  text << "Distortion: " << (d.empty() ? std::string("none") : "k1 " + fixedDecimals(d[0], 5) + " +- " +
                                                                   fixedDecimals(k_stddev[0], 5) + ", k2 " +
                                                                   fixedDecimals(d.size() > 1 ? d[1] : 0.0, 5) +
                                                                   " +- " + fixedDecimals(k_stddev[1], 5))
       << "\n";
  if (r.lens_fitted)
  {
    text << lensReport(r, file_lens);
  }
  text << "Coverage: " << percent(r.coverage) << " of the projector image, "
       << percent(double(r.decoded.lit) / double(std::max<std::size_t>(camera_pixels, 1)))
       << " of the camera image lit; " << r.decoded.decoded << " camera pixels decoded (" << r.decoded.full
       << " to the last bit), " << r.correspondences << " correspondences\n";
  text << (r.lens_fitted ? "Floor alone, the file's lens: " : "Residuals: ") << s.inliers << " inliers, " << s.outliers << " outliers; RMS " << fixedDecimals(s.rms_px, 3)
       << " px; on the floor median " << fixedDecimals(s.median_mm, 2) << " mm, max " << fixedDecimals(s.max_mm, 2)
       << " mm\n";
  text << "Expected floor error (1 sigma):";
  for (const ExpectedError& e : s.expected)
  {
    text << " " << e.where << " " << fixedDecimals(e.mm, 2) << " mm;";
  }
  text << "\n";
  for (const std::string& w : s.warnings)
  {
    text << "Warning: " << w << "\n";
  }
  text << "Took " << fixedDecimals(timing.total, 1) << " s (showing and capturing " << timing.patterns
       << " patterns " << fixedDecimals(timing.capture, 1) << " s, decoding and solving "
       << fixedDecimals(timing.solve, 2) << " s)\n";
  return text.str();
}
}  // namespace

int runCameraCalibration(const CalibrateOptions& options, std::ostream& out, std::ostream& err)
{
  const auto start = std::chrono::steady_clock::now();
  CalibrationInput file;
  if (const int status = loadCalibrationInput(options, file, err); status != kExitOk)
  {
    return status;
  }
  CameraCalibrationInput input;
  const LensCalibration projector = toLensCalibration(file.file.info);
  input.fit_distortion = !options.keep_distortion;
  input.board = options.board;
  if (const LensCheck check = LensDistortion::fromCalibration(projector, input.distortion); !check.ok())
  {
    return reportError(err, file.file.path + ": unusable distortion: " + check.error);
  }
  // The pixels the display will draw with the calibration written: through a distortion it draws
  // with K (P is a rectified camera's), without one with P (PinholeModel::fromCalibration).
  const bool drawn_through_k = input.fit_distortion || !input.distortion.none();
  if (const LensCheck check = drawn_through_k ? PinholeModel::rawFromCalibration(projector, input.lens)
                                              : PinholeModel::fromCalibration(projector, input.lens);
      !check.ok())
  {
    return reportError(err, file.file.path + ": unusable lens: " + check.error);
  }
  const std::string floor_frame = options.floor_frame.empty() ? options.frame : options.floor_frame;

  tf2_ros::Buffer tf;
  tf2_ros::TransformListener listener(tf);
  PatternCaptureOptions capture_options;
  capture_options.image_topic = options.image;
  capture_options.pattern_topic = options.pattern_topic;
  capture_options.settle = options.settle;
  PatternCapture capture(capture_options);
  err << "calibrate_projector: waiting for the projector (" << options.pattern_topic << ") and the camera ("
      << options.image << ")" << std::endl;
  if (const std::string problem = capture.waitUntilReady(10.0); !problem.empty())
  {
    return reportError(err, problem + " (nothing written)");
  }
  input.camera = toLensCalibration(capture.cameraInfo());
  std::string tf_error;
  if (!lookup(tf, floor_frame, capture.cameraFrame(), 3.0, input.floor_T_camera, tf_error))
  {
    return reportError(err, "no tf from the camera's frame '" + capture.cameraFrame() + "' to the floor frame '" +
                                floor_frame + "': " + tf_error + " (nothing written)");
  }
  RigidTransform base_T_floor;
  if (floor_frame != options.frame && !lookup(tf, options.frame, floor_frame, 3.0, base_T_floor, tf_error))
  {
    return reportError(err, "no tf from the floor frame '" + floor_frame + "' to '" + options.frame + "': " + tf_error +
                                " (nothing written)");
  }
  ProjectorMount prior;       // in the floor frame, for the solver
  ProjectorMount prior_base;  // in --frame, for the report
  RigidTransform floor_T_projector;
  if (lookup(tf, floor_frame, options.projector_frame, 1.0, floor_T_projector, tf_error))
  {
    prior = mountOfOpticalPose(floor_T_projector);
    prior_base = mountOfOpticalPose(base_T_floor * floor_T_projector);
    input.prior = &prior;
  }
  else
  {
    err << "calibrate_projector: no tf of the projector's frame '" << options.projector_frame
        << "': solving without the current mount as a start" << std::endl;
  }

  Timing timing;
  const auto capture_start = std::chrono::steady_clock::now();
  const std::vector<PatternFrame> frames = grayCodeFrames(int(input.lens.width()), int(input.lens.height()));
  std::vector<cv::Mat> captures(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    err << "calibrate_projector: [" << i + 1 << "/" << frames.size() << "] " << frames[i].name << std::endl;
    const std::string problem = capture.capture(frames[i].image, frames[i].name, captures[i]);
    if (!problem.empty())
    {
      return reportError(err, problem + " (nothing written)");
    }
  }
  capture.end();
  const auto solve_start = std::chrono::steady_clock::now();
  timing.capture = std::chrono::duration<double>(solve_start - capture_start).count();
  timing.patterns = frames.size();
  err << "calibrate_projector: decoding and solving" << std::endl;
  const CameraCalibrationResult result = solveFromCaptures(input, captures);
  timing.solve = std::chrono::duration<double>(std::chrono::steady_clock::now() - solve_start).count();
  if (!result.error.empty())
  {
    return reportError(err, result.error + " (nothing written)");
  }
  const RigidTransform base_T_optical =
      base_T_floor * (result.lens_fitted ? result.lens_fit.parent_T_optical : result.solution.parent_T_optical);
  MountSolution mount;
  mount.ok = true;
  mount.mount = mountOfOpticalPose(base_T_optical);
  mount.parent_T_optical = base_T_optical;
  mount.rms_px = result.lens_fitted ? result.lens_fit.rms_px : result.solution.rms_px;
  mount.rms_mm = result.lens_fitted ? result.lens_fit.floor_rms_mm : result.solution.rms_mm;

  std::vector<std::pair<std::string, std::string>> files;
  if (!options.output.empty())
  {
    files.emplace_back(options.output,
                       mountFileYaml(options.frame, mount,
                                     "# Projector mount solved by calibrate_projector --camera (" + options.image +
                                         ", " + options.camera_info + ").\n"));
  }
  if (!options.output_calibration.empty())
  {
    std::ostringstream yaml;
    // --keep-distortion: the file's D (what the solve used); --board: the fitted K, P = [K | 0].
    sensor_msgs::CameraInfo written = options.keep_distortion
                                          ? file.file.info
                                          : withDistortion(file.file.info, result.lens_fitted
                                                                               ? result.lens_fit.distortion
                                                                               : result.solution.distortion);
    if (result.lens_fitted)
    {
      written = withLens(written, result.lens_fit.lens);
    }
    if (!camera_calibration_parsers::writeCalibrationYml(yaml, file.file.camera_name, written))
    {
      return reportError(err, options.output_calibration + ": the calibration could not be formatted (nothing written)");
    }
    files.emplace_back(options.output_calibration, yaml.str());
  }
  if (const std::string error = writeTextFiles(files); !error.empty())
  {
    return reportError(err, error + " (no file written)");
  }
  timing.total = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out << report(result, mount.mount, options.frame, input.prior != nullptr ? &prior_base : nullptr, timing,
                captures.empty() ? 0 : captures[0].total(), input.lens);
  if (!options.output.empty())
  {
    out << "Mount written to " << options.output << ": projector.launch mount_file:=" << options.output << "\n";
  }
  if (!options.output_calibration.empty())
  {
    out << "Calibration written to " << options.output_calibration
        << (result.lens_fitted ? (options.keep_distortion ? " (K fitted, P = K, D kept)" : " (K fitted, D = k1 k2 0 0 0, P = K)")
                               : (options.keep_distortion ? " (unchanged: --keep-distortion)" : " (D = k1 k2 0 0 0, P = K)"))
        << ": calibration_file:=" << options.output_calibration << "\n";
  }
  return kExitOk;
}
}  // namespace rviz_projector
