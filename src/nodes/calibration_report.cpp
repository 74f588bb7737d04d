#include "rviz_projector/nodes/calibration_report.h"

#include <cmath>
#include <iomanip>
#include <sstream>

namespace rviz_projector
{
namespace
{
std::string fixed(double value, int decimals)
{
  std::ostringstream text;
  text.setf(std::ios::fixed);
  text.precision(decimals);
  text << (value == 0.0 ? 0.0 : value);  // no "-0.0"
  return text.str();
}

double degrees(double radians)
{
  return radians * 180.0 / M_PI;
}
}  // namespace

std::string launchArguments(const std::string& parent_frame, const ProjectorMount& mount)
{
  return "parent_frame:=" + parent_frame + " x:=" + fixed(mount.x, 6) + " y:=" + fixed(mount.y, 6) +
         " z:=" + fixed(mount.z, 6) + " roll:=" + fixed(mount.roll, 6) + " pitch:=" + fixed(mount.pitch, 6) +
         " yaw:=" + fixed(mount.yaw, 6);
}

std::string solutionReport(const std::string& parent_frame, const MountSolution& solution,
                           const std::string& mount_file)
{
  const ProjectorMount& m = solution.mount;
  std::ostringstream text;
  text << "Projector mount in " << parent_frame << " (" << solution.residuals.size() << " points, "
       << solution.outliers.size() << " rejected as outliers):\n"
       << "  x " << fixed(m.x, 4) << " m, y " << fixed(m.y, 4) << " m, z " << fixed(m.z, 4) << " m, roll "
       << fixed(degrees(m.roll), 3) << " deg, pitch " << fixed(degrees(m.pitch), 3) << " deg, yaw "
       << fixed(degrees(m.yaw), 3) << " deg\n"
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
    text << std::setw(7) << r.id << std::setw(10) << fixed(r.px, 3) << std::setw(10) << fixed(r.mm, 2) << "  "
         << (r.outlier ? "yes" : "no") << "\n";
  }
  text << "RMS over the inliers: " << fixed(solution.rms_px, 3) << " px, " << fixed(solution.rms_mm, 2) << " mm\n";
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
          text << " " << id << " (" << fixed(r.px, 1) << " px, " << fixed(r.mm, 1) << " mm)";
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
      text << "  " << e.where << " (x " << fixed(e.world.x, 2) << ", y " << fixed(e.world.y, 2)
           << "): " << fixed(e.mm, 1) << " mm\n";
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
