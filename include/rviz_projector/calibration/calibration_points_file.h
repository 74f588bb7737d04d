// The calibration points file of calibrate_projector (issue 12): reading points.yaml, writing its
// template (--pattern) and writing it from clicked points (--clicked-points).
//
//   frame: base_link            # frame the points are measured in; its z = 0 is the floor
//   points:
//     - {id: 1, u: 192.0, v: 120.0, x: 2.013, y: 0.871}      # z: 0.0 unless given
//
// u, v (projector pixels) may be left out: they then come from the crosshair pattern by id. The
// template writes `x: null, y: null` for the user to fill in; a point still holding null is
// "not measured" and refused by name. Every problem comes back as one sentence naming the file,
// the point (id and entry number) and the field.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"

namespace rviz_projector
{
/// Coordinates beyond this (metres) look like millimetres typed into a file in metres: the core's
/// limit, checked here too so that the message names the point and the field.
constexpr double kMaxPointCoordinate = kMaxFloorPointCoordinate;

struct CalibrationPoints
{
  std::string frame;
  std::vector<FloorPoint> points;
};

/**
 * Reads and checks a points file. `pattern` supplies u, v for points that leave them out (an id
 * not in it is "unknown"); `pattern_name` describes it in messages (e.g. "the 3x3 pattern").
 * Returns "" on success, else "<file>: <problem>". Checks: YAML syntax, the structure, numbers
 * (finite, metres not millimetres), ids (whole, >= 1, no duplicates), x/y filled in.
 */
std::string readCalibrationPoints(const std::string& path, const std::vector<Crosshair>& pattern,
                                  const std::string& pattern_name, CalibrationPoints& out);

/// The template --pattern prints: a comment header saying what to fill in, the frame, and one
/// line per crosshair with its id, u, v and `x: null, y: null`.
std::string calibrationPointsTemplate(const std::vector<Crosshair>& pattern, const std::string& frame,
                                      const std::string& header_comment);

/// A filled-in points file (the --clicked-points mode writes it).
std::string calibrationPointsYaml(const CalibrationPoints& points, const std::string& header_comment);

/// Writes `text` to `path` through a temporary file renamed into place; "" or the problem.
std::string writeTextFile(const std::string& path, const std::string& text);
/// Writes every (path, text) all or nothing: each to a temporary file first; only when all of them
/// are written are they renamed into place. A failure leaves none of the files changed.
std::string writeTextFiles(const std::vector<std::pair<std::string, std::string>>& files);
}  // namespace rviz_projector
