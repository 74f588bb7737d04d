// calibrate_projector --clicked-points (issue 12): the crosshairs' floor positions from rviz's
// Publish Point tool instead of a tape measure. A ROS node: subscribes to /clicked_point
// (geometry_msgs/PointStamped), asks for the crosshairs one by one on `out`, transforms each
// clicked point into --frame with tf2 (the robot must be localised: the point is clicked in the
// map), writes --points-out and solves as from a points file.
#pragma once

#include <ostream>

#include "rviz_projector/calibration/calibrate_projector_options.h"

namespace rviz_projector
{
/// Runs the mode; ros::init must have been called. Returns the exit status (CalibrateExit).
int runClickedPoints(const CalibrateOptions& options, std::ostream& out, std::ostream& err);
}  // namespace rviz_projector
