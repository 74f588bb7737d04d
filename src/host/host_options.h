// Command line of projector_host (ROS remapping arguments already removed).
#pragma once

#include <string>
#include <vector>

namespace rviz_projector
{
/// Exit statuses of projector_host (README, "Running on the robot").
enum HostExit : int
{
  kHostExitOk = 0,         ///< ended by SIGINT/SIGTERM or ROS shutdown
  kHostExitBadConfig = 1,  ///< config missing, unreadable, broken, or without a ProjectorCamera
  kHostExitUsage = 2,      ///< bad command line
  kHostExitNoDisplay = 3,  ///< no X display / no OpenGL
};

struct HostOptions
{
  std::string config;  ///< the .rviz file
  bool watch = false;  ///< reload when the file changes
  double keep_alive = 1.0;  ///< seconds; 0: no keep-alive frames (RenderPolicy, render_policy.h)
  /// Run every enabled display, also those no ProjectorCamera shows (HostSession parks them).
  bool all_displays = false;
};

struct HostOptionsResult
{
  HostOptions options;
  bool help = false;   ///< --help: print usage, exit 0
  std::string error;   ///< non-empty: print it and the usage, exit kHostExitUsage
};

HostOptionsResult parseHostOptions(const std::vector<std::string>& args);
std::string hostUsage();
}  // namespace rviz_projector
