// The mount file (issue 12): calibrate_projector --output writes it, projector.launch mount_file:=
// reads it (mount_tf_publisher).
//
//   parent_frame: base_link
//   x: 0.150          # metres, in parent_frame
//   y: 0.000
//   z: 1.200
//   roll: 0.0         # radians, projector.launch's convention (positive pitch: beam down)
//   pitch: 0.876
//   yaw: 0.0
//   rms_px: 0.42      # the rest is the solution's quality, for the reader; not read back
//   rms_mm: 2.1
//   outliers: []
//   residuals: [{id: 1, px: 0.3, mm: 1.4}, ...]
#pragma once

#include <string>

#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/projector_mount.h"

namespace rviz_projector
{
struct MountFile
{
  std::string parent_frame;
  ProjectorMount mount;
};

/// The text of a mount file for a solution (`header_comment`: lines starting with '#').
std::string mountFileYaml(const std::string& parent_frame, const MountSolution& solution,
                          const std::string& header_comment);

/**
 * Reads a mount file: parent_frame (a frame name) and x, y, z, roll, pitch, yaw (finite numbers)
 * are required; the quality fields are not read. Returns "" or "<file>: <problem>" naming the field.
 */
std::string readMountFile(const std::string& path, MountFile& out);
}  // namespace rviz_projector
