// Loading and checking a projector calibration file (the camera_calibration_parsers YAML format),
// for projector_info_publisher. Every problem comes back as one sentence that names the file and
// the field, so a user can fix the file without reading code.
#pragma once

#include <string>
#include <vector>

#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/lens_calibration.h"

namespace rviz_projector
{
struct CalibrationFile
{
  /// File actually read (a package:// or file:// URL resolved to a path).
  std::string path;
  /// camera_name from the file ("unknown" when absent, as camera_calibration_parsers does).
  std::string camera_name;
  /// The calibration; header (frame, stamp) left empty for the caller to fill in.
  sensor_msgs::CameraInfo info;
  /// Non-fatal remarks worth a ROS_WARN (e.g. K and P disagree, distortion not applied).
  std::vector<std::string> warnings;
};

/**
 * Turns `package://<package>/<path>`, `file://<absolute path>` or a plain path into a file path.
 * Returns an empty string on success, else the problem (e.g. "package 'foo' not found").
 */
std::string resolveCalibrationUrl(const std::string& url, std::string& path);

/// `path` itself when absolute (or `base` is empty), else `base`/`path`: how projector.launch's
/// nodes take a relative calibration_file or mount_file from the directory roslaunch ran in.
std::string inDirectory(const std::string& path, const std::string& base);

/**
 * Reads a calibration with camera_calibration_parsers and checks it: structure of the YAML (every
 * field camera_calibration_parsers needs, matrix sizes, numbers), image size, and that
 * rviz_projector's PinholeModel accepts the lens. Returns an empty string on success, else
 * "<file>: <problem>", e.g. "/x.yaml: missing field 'camera_matrix'".
 */
std::string loadCalibrationFile(const std::string& url, CalibrationFile& out);
}  // namespace rviz_projector
