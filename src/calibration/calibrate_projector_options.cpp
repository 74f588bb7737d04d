#include "rviz_projector/calibration/calibrate_projector_options.h"

#include <cstdlib>

namespace rviz_projector
{
namespace
{
bool parseCount(const std::string& text, int& value)
{
  if (text.empty() || text.size() > 3 || text.find_first_not_of("0123456789") != std::string::npos)
  {
    return false;
  }
  value = std::atoi(text.c_str());
  return value >= 1 && value <= CrosshairPatternSize::kMaxRowsCols;
}

/// Millimetres, 0.1 .. 100, into metres.
bool parseTapeError(const std::string& text, double& metres)
{
  char* end = nullptr;
  const double mm = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(mm >= 0.1 && mm <= 100.0))
  {
    return false;
  }
  metres = mm / 1000.0;
  return true;
}

/// Seconds, 0 .. 5 (well below the ProjectorCamera's default Pattern timeout, 10 s).
bool parseSettle(const std::string& text, double& seconds)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || *end != '\0' || !(value >= 0.0 && value <= 5.0))
  {
    return false;
  }
  seconds = value;
  return true;
}
}  // namespace

std::string calibrateUsage()
{
  return "Usage:\n"
         "  calibrate_projector --pattern --camera-info CAL.yaml [--rows R --cols C] [--frame F] > points.yaml\n"
         "      print the points template: every crosshair's id and pixel u, v, with x, y to fill in\n"
         "  calibrate_projector --camera-info CAL.yaml --points points.yaml [--output mount.yaml]\n"
         "                      [--rows R --cols C] [--tape-error MM]\n"
         "                      [--fit-intrinsics | --fit-distortion] [--output-calibration NEW_CAL.yaml]\n"
         "      solve the projector's mount from the measured points and print it as projector.launch\n"
         "      arguments, with the residuals, outliers and the expected floor error\n"
         "  calibrate_projector --clicked-points --camera-info CAL.yaml --points-out points.yaml\n"
         "                      [--frame base_link] [--output mount.yaml] [--rows R --cols C]\n"
         "      a ROS node: asks for the crosshairs one by one, takes each from rviz's Publish Point tool\n"
         "      (/clicked_point), transforms it into --frame with tf, writes points.yaml and solves\n"
         "  calibrate_projector --camera --camera-info CAL.yaml --image /camera/image_raw [--frame base_link]\n"
         "                      [--floor-frame F] [--projector-frame F] [--pattern-topic T] [--settle S]\n"
         "                      [--keep-distortion] [--board COLSxROWS:SQUARE_M] [--output mount.yaml]\n"
         "                      [--output-calibration NEW_CAL.yaml]\n"
         "      a ROS node: shows Gray code patterns through the running projector (the ProjectorCamera's\n"
         "      Pattern topic, in rviz or projector_host), captures each with the robot's camera, decodes\n"
         "      which projector pixel lights each camera pixel, and solves the mount and k1, k2 (fx, fy, cx,\n"
         "      cy stay the file's: a flat floor cannot pin them; --board fits them too)\n"
         "Options:\n"
         "  --camera-info CAL.yaml   the projector's calibration (path, package://pkg/path or file:///path)\n"
         "  --rows R, --cols C       crosshair pattern size, 1.." +
         std::to_string(CrosshairPatternSize::kMaxRowsCols) + " (default " +
         std::to_string(CrosshairPatternSize::kDefaultRows) + "x" + std::to_string(CrosshairPatternSize::kDefaultCols) +
         "); must match the display's\n"
         "  --frame F                frame of the points (default base_link)\n"
         "  --tape-error MM          how accurately the points were measured, 1 sigma in mm (default " +
         std::to_string(static_cast<int>(MountSolverOptions().tape_error * 1000.0 + 0.5)) +
         "):\n"
         "                           sets the outlier threshold and the expected error\n"
         "  --fit-intrinsics         also fit fx, fy, cx, cy (needs points off the floor, z given)\n"
         "  --fit-distortion         also fit the lens distortion k1, k2 (plumb_bob; needs 8+ points\n"
         "                           reaching the image corners, e.g. --rows 5 --cols 5, measured to 1 mm)\n"
         "  --output-calibration NEW_CAL.yaml   write the calibration with the fitted numbers\n"
         "  --image TOPIC            --camera: the camera's sensor_msgs/Image (its CameraInfo on the sibling\n"
         "                           camera_info topic, D included; default /camera/image_raw)\n"
         "  --floor-frame F          --camera: the floor is z = 0 of F (default: --frame)\n"
         "  --projector-frame F      --camera: the projector's optical frame in tf, the current mount as the\n"
         "                           start (default projector_optical_frame; without it: solved from scratch)\n"
         "  --pattern-topic T        --camera: the ProjectorCamera's Pattern topic (default /projector/pattern)\n"
         "  --settle S               --camera: seconds from the projector's acknowledgement to the first camera\n"
         "                           frame used (projector lag + camera exposure; default 0.15)\n"
         "  --keep-distortion        --camera: keep the file's D instead of fitting k1, k2\n"
         "  --board COLSxROWS:SQUARE_M   --camera: a printed checkerboard (inner corners, square side in metres,\n"
         "                           e.g. 7x5:0.06) propped up 30-60 deg from the floor in the lit patch, in the\n"
         "                           camera's view: fx, fy, cx, cy are fitted too\n"
         "Exit status: 0 solved/written, 1 bad input or no solution (nothing written), 2 bad command line.\n";
}

std::string parseCalibrateOptions(const std::vector<std::string>& args, CalibrateOptions& out)
{
  out = CalibrateOptions();
  bool pattern = false;
  bool clicked = false;
  bool camera = false;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (arg == "-h" || arg == "--help")
    {
      out.mode = CalibrateOptions::Mode::Help;
      return "";
    }
    if (arg == "--pattern")
    {
      pattern = true;
      continue;
    }
    if (arg == "--clicked-points")
    {
      clicked = true;
      continue;
    }
    if (arg == "--fit-intrinsics")
    {
      out.fit_intrinsics = true;
      continue;
    }
    if (arg == "--fit-distortion")
    {
      out.fit_distortion = true;
      continue;
    }
    if (arg == "--camera")
    {
      camera = true;
      continue;
    }
    if (arg == "--keep-distortion")
    {
      out.keep_distortion = true;
      continue;
    }
    std::string* text = nullptr;
    int* count = nullptr;
    double* tape_error = nullptr;
    double* settle = nullptr;
    std::string board;
    bool is_board = false;
    if (arg == "--camera-info")
      text = &out.camera_info;
    else if (arg == "--points")
      text = &out.points;
    else if (arg == "--output")
      text = &out.output;
    else if (arg == "--output-calibration")
      text = &out.output_calibration;
    else if (arg == "--points-out")
      text = &out.points_out;
    else if (arg == "--frame")
      text = &out.frame;
    else if (arg == "--image")
      text = &out.image;
    else if (arg == "--pattern-topic")
      text = &out.pattern_topic;
    else if (arg == "--floor-frame")
      text = &out.floor_frame;
    else if (arg == "--projector-frame")
      text = &out.projector_frame;
    else if (arg == "--settle")
      settle = &out.settle;
    else if (arg == "--board")
      text = &board, is_board = true;
    else if (arg == "--rows")
      count = &out.rows;
    else if (arg == "--tape-error")
      tape_error = &out.tape_error;
    else if (arg == "--cols")
      count = &out.cols;
    else
      return "unknown argument '" + arg + "'";
    if (i + 1 >= args.size() || args[i + 1].empty())
    {
      return arg + " needs a value";
    }
    const std::string& value = args[++i];
    if (text != nullptr)
    {
      *text = value;
      BoardSpec spec;
      std::string error;
      if (is_board && !parseBoardSpec(value, spec, error))
      {
        return arg + ": " + error;
      }
      if (is_board)
      {
        out.board = spec;
      }
    }
    else if (settle != nullptr)
    {
      if (!parseSettle(value, *settle))
      {
        return arg + " must be seconds from 0 to 5 (got '" + value + "')";
      }
    }
    else if (tape_error != nullptr)
    {
      if (!parseTapeError(value, *tape_error))
      {
        return arg + " must be millimetres from 0.1 to 100 (got '" + value + "')";
      }
    }
    else if (!parseCount(value, *count))
    {
      return arg + " must be a whole number from 1 to " + std::to_string(CrosshairPatternSize::kMaxRowsCols) +
             " (got '" + value + "')";
    }
  }
  if (int(pattern) + int(clicked) + int(camera) > 1)
  {
    return "--pattern, --clicked-points and --camera exclude each other";
  }
  out.mode = pattern   ? CalibrateOptions::Mode::Pattern
             : clicked ? CalibrateOptions::Mode::ClickedPoints
             : camera  ? CalibrateOptions::Mode::Camera
                       : CalibrateOptions::Mode::Solve;
  if (out.camera_info.empty())
  {
    return "--camera-info CAL.yaml is required (the projector's calibration)";
  }
  if (out.frame.empty())
  {
    return "--frame needs a frame name";
  }
  if (pattern && (!out.points.empty() || !out.output.empty() || out.fit_intrinsics || out.fit_distortion ||
                  !out.points_out.empty() ||
                  out.tape_error != MountSolverOptions().tape_error))
  {
    return "--pattern only prints the template: it takes --camera-info, --rows, --cols and --frame";
  }
  if (out.mode == CalibrateOptions::Mode::Solve && out.points.empty())
  {
    return "--points points.yaml is required to solve (or --pattern to print the template, --clicked-points "
           "to click them in rviz)";
  }
  if (out.mode == CalibrateOptions::Mode::Solve && !out.points_out.empty())
  {
    return "--points-out is for --clicked-points";
  }
  if (clicked && !out.points.empty())
  {
    return "--clicked-points takes the points from rviz: use --points-out for the file to write";
  }
  if (clicked && out.points_out.empty())
  {
    return "--clicked-points needs --points-out points.yaml (the file the clicked points are written to)";
  }
  if (out.fit_intrinsics && out.fit_distortion)
  {
    return "--fit-intrinsics and --fit-distortion exclude each other: fit the intrinsics first (points off the "
           "floor), then the distortion with the fitted calibration";
  }
  if (camera && (!out.points.empty() || !out.points_out.empty() || out.fit_intrinsics || out.fit_distortion))
  {
    return "--camera takes no points (--points, --points-out) and fits k1, k2 itself (no --fit-intrinsics, "
           "--fit-distortion)";
  }
  if (!camera && (out.keep_distortion || out.image != CalibrateOptions().image ||
                  out.pattern_topic != CalibrateOptions().pattern_topic || !out.floor_frame.empty() ||
                  out.projector_frame != CalibrateOptions().projector_frame || out.settle != CalibrateOptions().settle ||
                  out.board))
  {
    return "--image, --pattern-topic, --floor-frame, --projector-frame, --settle, --keep-distortion and --board are "
           "for --camera";
  }
  if (camera && (out.image.empty() || out.pattern_topic.empty()))
  {
    return "--image and --pattern-topic need a topic";
  }
  if (!out.output_calibration.empty() && !out.fit_intrinsics && !out.fit_distortion && !camera)
  {
    return "--output-calibration needs --fit-intrinsics, --fit-distortion or --camera";
  }
  return "";
}
}  // namespace rviz_projector
