#include "host_options.h"

namespace rviz_projector
{
HostOptionsResult parseHostOptions(const std::vector<std::string>& args)
{
  HostOptionsResult result;
  for (const std::string& arg : args)
  {
    if (arg == "-h" || arg == "--help")
    {
      result.help = true;
    }
    else if (arg == "--watch" || arg == "-w")
    {
      result.options.watch = true;
    }
    else if (!arg.empty() && arg[0] == '-')
    {
      result.error = "unknown option '" + arg + "'";
      return result;
    }
    else if (result.options.config.empty())
    {
      result.options.config = arg;
    }
    else
    {
      result.error = "more than one config file given ('" + result.options.config + "' and '" + arg + "')";
      return result;
    }
  }
  if (!result.help && result.options.config.empty())
  {
    result.error = "no config file given";
  }
  return result;
}

std::string hostUsage()
{
  return "usage: rosrun rviz_projector projector_host [--watch] CONFIG.rviz\n"
         "\n"
         "Shows the output window of every ProjectorCamera in CONFIG.rviz (a config saved from rviz),\n"
         "with all its displays, but without rviz's main window and without rendering a main view.\n"
         "\n"
         "  --watch, -w   reload when CONFIG.rviz changes (as 'rosservice call ~reload' does)\n"
         "  --help, -h    this text\n"
         "\n"
         "Services: ~reload (std_srvs/Trigger). Diagnostics on /diagnostics.\n"
         "Exit status: 0 stopped (SIGINT, SIGTERM, ROS shutdown), 1 config missing, broken or without a\n"
         "ProjectorCamera, 2 bad command line, 3 no X display.\n";
}
}  // namespace rviz_projector
