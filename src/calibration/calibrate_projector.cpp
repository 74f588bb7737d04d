// calibrate_projector (issue 12): the projector's mount from crosshairs measured on the floor.
//
//   calibrate_projector --pattern --camera-info CAL.yaml [--rows R --cols C] > points.yaml
//   calibrate_projector --camera-info CAL.yaml --points points.yaml [--output mount.yaml]
//   calibrate_projector --clicked-points --camera-info CAL.yaml --points-out points.yaml [--output mount.yaml]
//   calibrate_projector --camera --camera-info CAL.yaml --image /camera/image_raw [--output mount.yaml]
//
// The modes live in calibration_run.cpp, clicked_points.cpp and camera_calibration.cpp; this is only
// the dispatch.
// Exit status: 0 ok, 1 bad input or no solution (message on stderr, nothing written), 2 usage.

#include <ros/ros.h>

#include <iostream>
#include <string>
#include <vector>

#include "rviz_projector/calibration/calibrate_projector_options.h"
#include "rviz_projector/calibration/camera_calibration.h"
#include "rviz_projector/calibration/calibration_run.h"
#include "rviz_projector/calibration/clicked_points.h"

int main(int argc, char** argv)
{
  using rviz_projector::CalibrateOptions;
  std::vector<std::string> args(argv + 1, argv + argc);
  bool node = false;
  for (const std::string& arg : args)
  {
    node = node || arg == "--clicked-points" || arg == "--camera";
  }
  if (node)
  {
    // A ROS node only in these modes: ros::init also takes its remapping arguments (__name:= ...) out.
    ros::init(argc, argv, "calibrate_projector", ros::init_options::AnonymousName);
    args.assign(argv + 1, argv + argc);
  }

  CalibrateOptions options;
  const std::string usage_error = rviz_projector::parseCalibrateOptions(args, options);
  if (!usage_error.empty())
  {
    std::cerr << "calibrate_projector: " << usage_error << "\n\n" << rviz_projector::calibrateUsage();
    return rviz_projector::kExitUsage;
  }
  switch (options.mode)
  {
    case CalibrateOptions::Mode::Help:
      std::cout << rviz_projector::calibrateUsage();
      return rviz_projector::kExitOk;
    case CalibrateOptions::Mode::Pattern:
      return rviz_projector::runPattern(options, std::cout, std::cerr);
    case CalibrateOptions::Mode::ClickedPoints:
      return rviz_projector::runClickedPoints(options, std::cout, std::cerr);
    case CalibrateOptions::Mode::Camera:
      return rviz_projector::runCameraCalibration(options, std::cout, std::cerr);
    case CalibrateOptions::Mode::Solve:
      break;
  }
  return rviz_projector::runSolve(options, std::cout, std::cerr);
}
