// calibrate_projector --camera (issue 24): the projector's mount and distortion from structured
// light seen by the robot's own camera.
//
//   1. PatternCapture shows white, black and OpenCV's Gray code patterns (core grayCodeFrames)
//      through the ProjectorCamera's Pattern topic and captures a camera frame of each;
//   2. solveFromCaptures (core, structured_light_calibration.h): decoding, floor correspondences,
//      the mount and k1, k2 (fx, fy, cx, cy kept: a flat floor cannot pin them);
//   3. runCameraCalibration reports coverage, residuals, the expected floor error, and writes the
//      mount file and the calibration (D = k1 k2 0 0 0, P = K) only when everything held.
// Each refusal is one sentence and writes nothing.
#pragma once

#include <ostream>
#include <string>
#include "rviz_projector/calibration/calibrate_projector_options.h"

namespace rviz_projector
{
/// The whole --camera mode (a ROS node: ros::init already called). Exit status as CalibrateExit.
int runCameraCalibration(const CalibrateOptions& options, std::ostream& out, std::ostream& err);
}  // namespace rviz_projector
