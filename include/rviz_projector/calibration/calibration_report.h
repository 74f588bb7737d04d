// What calibrate_projector prints after solving (issue 12): the mount as projector.launch
// arguments, the residuals per point, the RMS, the outliers, the expected floor error, warnings;
// and the calibration with fitted intrinsics (--fit-intrinsics).
#pragma once

#include <string>

#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/projector_mount.h"

namespace rviz_projector
{
/// "parent_frame:=base_link x:=0.150000 y:=... z:=... roll:=... pitch:=... yaw:=..."
std::string launchArguments(const std::string& parent_frame, const ProjectorMount& mount);

/// The whole report (several lines). `mount_file`: the file written by --output ("" when none).
std::string solutionReport(const std::string& parent_frame, const MountSolution& solution,
                           const std::string& mount_file);

/**
 * `original` with fx, fy, cx, cy of K and P replaced by the fitted lens's (its ROI and binning
 * undone, so the numbers describe the full image as the calibration file does).
 */
sensor_msgs::CameraInfo fittedCameraInfo(const sensor_msgs::CameraInfo& original, const PinholeModel& fitted);
}  // namespace rviz_projector
