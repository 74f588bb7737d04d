#include "rviz_projector/calibration/clicked_points.h"

#include "rviz_projector/calibration/number_format.h"

#include <cmath>
#include <deque>
#include <sstream>

#include <geometry_msgs/PointStamped.h>
#include <ros/ros.h>
#include <tf2_geometry_msgs/tf2_geometry_msgs.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "rviz_projector/calibration/calibration_run.h"

namespace rviz_projector
{
namespace
{
const char* const kTopic = "/clicked_point";

/// Waits for the next clicked point that tf can bring into `frame`; false when ROS shuts down.
bool nextPoint(std::deque<geometry_msgs::PointStamped>& queue, const tf2_ros::Buffer& tf, const std::string& frame,
               Vec3& point, std::ostream& out)
{
  ros::WallRate poll(50.0);
  while (ros::ok())
  {
    ros::spinOnce();
    if (queue.empty())
    {
      poll.sleep();
      continue;
    }
    const geometry_msgs::PointStamped clicked = queue.front();
    queue.pop_front();
    if (!std::isfinite(clicked.point.x) || !std::isfinite(clicked.point.y) || !std::isfinite(clicked.point.z))
    {
      out << "  the clicked point is not finite; click again" << std::endl;
      continue;
    }
    geometry_msgs::PointStamped transformed;
    try
    {
      // Stamp 0 (or a stamp tf has not caught up with): the latest transform, waited for briefly.
      const geometry_msgs::TransformStamped transform = tf.lookupTransform(
          frame, clicked.header.frame_id, clicked.header.stamp, ros::Duration(1.0));
      tf2::doTransform(clicked, transformed, transform);
    }
    catch (const tf2::TransformException& e)
    {
      try
      {
        const geometry_msgs::TransformStamped transform =
            tf.lookupTransform(frame, clicked.header.frame_id, ros::Time(0), ros::Duration(1.0));
        tf2::doTransform(clicked, transformed, transform);
      }
      catch (const tf2::TransformException& latest)
      {
        out << "  cannot transform the clicked point from '" << clicked.header.frame_id << "' into '" << frame
            << "' (" << latest.what() << "); is the robot localised? Click again" << std::endl;
        continue;
      }
    }
    point = {transformed.point.x, transformed.point.y, transformed.point.z};
    return true;
  }
  return false;
}
}  // namespace

int runClickedPoints(const CalibrateOptions& options, std::ostream& out, std::ostream& err)
{
  CalibrationInput input;
  const int status = loadCalibrationInput(options, input, err);
  if (status != kExitOk)
  {
    return status;
  }
  if (!ros::master::check())
  {
    return reportError(err, "--clicked-points: no ROS master at " + ros::master::getURI() +
                                " (start the robot or roscore, and rviz with the Publish Point tool)");
  }
  ros::NodeHandle nh;
  tf2_ros::Buffer tf;
  tf2_ros::TransformListener listener(tf, nh);
  std::deque<geometry_msgs::PointStamped> queue;
  const ros::Subscriber subscriber = nh.subscribe<geometry_msgs::PointStamped>(
      kTopic, 10, [&queue](const geometry_msgs::PointStamped::ConstPtr& msg) { queue.push_back(*msg); });

  out << "Set the ProjectorCamera's Test pattern to Crosshairs (" << options.rows << "x" << options.cols
      << "), then click each crosshair's centre in rviz with the Publish Point tool (" << kTopic
      << "); the points are taken into '" << options.frame << "'." << std::endl;
  CalibrationPoints points;
  points.frame = options.frame;
  const std::size_t count = input.pattern.size();
  for (const Crosshair& crosshair : input.pattern)
  {
    out << "Crosshair " << crosshair.id << " of " << count << " at pixel (u " << fixedDecimals(crosshair.pixel.x, 1)
        << ", v " << fixedDecimals(crosshair.pixel.y, 1) << "): click its centre" << std::endl;
    FloorPoint point;
    point.id = crosshair.id;
    point.pixel = crosshair.pixel;
    if (!nextPoint(queue, tf, options.frame, point.world, out))
    {
      return reportError(err, "interrupted after " + std::to_string(points.points.size()) + " of " +
                                  std::to_string(count) + " crosshairs: nothing written");
    }
    out << "  crosshair " << crosshair.id << ": x " << fixedDecimals(point.world.x, 3) << ", y "
        << fixedDecimals(point.world.y, 3) << ", z " << fixedDecimals(point.world.z, 3) << " m in " << options.frame << std::endl;
    points.points.push_back(point);
  }

  const std::string header = "# Crosshairs clicked in rviz (calibrate_projector --clicked-points), in " +
                             options.frame + ". Edit and solve again with --points.\n";
  const std::string error = writeTextFile(options.points_out, calibrationPointsYaml(points, header));
  if (!error.empty())
  {
    return reportError(err, error);
  }
  out << "Points written to " << options.points_out << "\n" << std::endl;
  const int solved = solveAndWrite(options, input, points, options.points_out, out, err);
  out << std::flush;
  return solved;
}
}  // namespace rviz_projector
