#include "rviz_projector/calibration/calibration_report.h"

#include "rviz_projector/calibration/number_format.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace rviz_projector
{
namespace
{
double degrees(double radians)
{
  return radians * 180.0 / M_PI;
}
}  // namespace

std::string launchArguments(const std::string& parent_frame, const ProjectorMount& mount)
{
  return "parent_frame:=" + parent_frame + " x:=" + fixedDecimals(mount.x, 6) + " y:=" + fixedDecimals(mount.y, 6) +
         " z:=" + fixedDecimals(mount.z, 6) + " roll:=" + fixedDecimals(mount.roll, 6) + " pitch:=" + fixedDecimals(mount.pitch, 6) +
         " yaw:=" + fixedDecimals(mount.yaw, 6);
}

std::string solutionReport(const std::string& parent_frame, const MountSolution& solution,
                           const std::string& mount_file)
{
  const ProjectorMount& m = solution.mount;
  std::ostringstream text;
  text << "Projector mount in " << parent_frame << " (" << solution.residuals.size() << " points, "
       << solution.outliers.size() << " rejected as outliers):\n"
       << "  x " << fixedDecimals(m.x, 4) << " m, y " << fixedDecimals(m.y, 4) << " m, z " << fixedDecimals(m.z, 4) << " m, roll "
       << fixedDecimals(degrees(m.roll), 3) << " deg, pitch " << fixedDecimals(degrees(m.pitch), 3) << " deg, yaw "
       << fixedDecimals(degrees(m.yaw), 3) << " deg\n"
       << "projector.launch arguments:\n"
       << "  " << launchArguments(parent_frame, m) << "\n";
  if (!mount_file.empty())
  {
    text << "  or: mount_file:=" << mount_file << " (written)\n";
  }
  text << "\nResiduals (measured point vs the solution):\n"
       << "     id        px        mm  outlier\n";
  for (const PointResidual& r : solution.residuals)
  {
    // An outlier's ray may miss its point's plane (z wrong): no finite residual, "miss".
    text << std::setw(7) << r.id << std::setw(10) << (std::isfinite(r.px) ? fixedDecimals(r.px, 3) : "miss")
         << std::setw(10) << (std::isfinite(r.mm) ? fixedDecimals(r.mm, 2) : "miss") << "  "
         << (r.outlier ? "yes" : "no") << "\n";
  }
  text << "RMS over the inliers: " << fixedDecimals(solution.rms_px, 3) << " px, " << fixedDecimals(solution.rms_mm, 2) << " mm\n";
  if (solution.outliers.empty())
  {
    text << "Outliers: none\n";
  }
  else
  {
    text << "Outliers (rejected, not used; re-measure them):";
    for (const int id : solution.outliers)
    {
      for (const PointResidual& r : solution.residuals)
      {
        if (r.id == id)
        {
          if (std::isfinite(r.mm))
          {
            text << " " << id << " (" << fixedDecimals(r.px, 1) << " px, " << fixedDecimals(r.mm, 1) << " mm)";
          }
          else
          {
            text << " " << id << " (its crosshair's ray cannot reach the point's z: check z)";
          }
        }
      }
    }
    text << "\n";
  }
  if (!solution.expected.empty())
  {
    text << "Expected floor error of this solution (1 sigma, from its covariance):\n";
    for (const ExpectedError& e : solution.expected)
    {
      text << "  " << e.where << " (x " << fixedDecimals(e.world.x, 2) << ", y " << fixedDecimals(e.world.y, 2)
           << "): " << fixedDecimals(e.mm, 1) << " mm\n";
    }
  }
  for (const std::string& warning : solution.warnings)
  {
    text << "warning: " << warning << "\n";
  }
  return text.str();
}

sensor_msgs::CameraInfo fittedCameraInfo(const sensor_msgs::CameraInfo& original, const PinholeModel& fitted)
{
  sensor_msgs::CameraInfo info = original;
  const double bx = original.binning_x == 0 ? 1.0 : original.binning_x;
  const double by = original.binning_y == 0 ? 1.0 : original.binning_y;
  const double fx = fitted.fx() * bx;
  const double fy = fitted.fy() * by;
  const double cx = fitted.cx() * bx + original.roi.x_offset;
  const double cy = fitted.cy() * by + original.roi.y_offset;
  info.K[0] = fx;
  info.K[2] = cx;
  info.K[4] = fy;
  info.K[5] = cy;
  info.P[0] = fx;
  info.P[2] = cx;
  info.P[5] = fy;
  info.P[6] = cy;
  return info;
}
}  // namespace rviz_projector
