#include "host_options.h"

#include <cmath>
#include <stdexcept>

namespace rviz_projector
{
HostOptionsResult parseHostOptions(const std::vector<std::string>& args)
{
  HostOptionsResult result;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    if (arg == "--keep-alive")
    {
      std::size_t used = 0;
      double seconds = -1.0;
      try
      {
        seconds = i + 1 < args.size() ? std::stod(args[i + 1], &used) : -1.0;
      }
      catch (const std::exception&)
      {
        used = 0;
      }
      if (i + 1 >= args.size() || used != args[i + 1].size() || !std::isfinite(seconds) || seconds < 0.0)
      {
        result.error = "--keep-alive needs a number of seconds >= 0";
        return result;
      }
      result.options.keep_alive = seconds;
      ++i;
    }
    else if (arg == "-h" || arg == "--help")
    {
      result.help = true;
    }
    else if (arg == "--watch" || arg == "-w")
    {
      result.options.watch = true;
    }
    else if (arg == "--all-displays")
    {
      result.options.all_displays = true;
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
  return "usage: rosrun rviz_projector projector_host [--watch] [--keep-alive SECONDS] [--all-displays]\n"
         "       CONFIG.rviz\n"
         "\n"
         "Shows the output window of every ProjectorCamera in CONFIG.rviz (a config saved from rviz),\n"
         "with all its displays, but without rviz's main window and without rendering a main view.\n"
         "\n"
         "  --watch, -w   reload when CONFIG.rviz changes (as 'rosservice call ~reload' does)\n"
         "  --keep-alive SECONDS   while a projector shows displays of other packages, render at least\n"
         "                this often (default 1; 0: only when their scene graph changes)\n"
         "  --all-displays   also run the displays that no ProjectorCamera shows (by default they are\n"
         "                not run: nothing else is shown here, and they only cost CPU)\n"
         "  --help, -h    this text\n"
         "\n"
         "Services: ~reload (std_srvs/Trigger). Diagnostics on /diagnostics.\n"
         "Exit status: 0 stopped (SIGINT, SIGTERM, ROS shutdown), 1 config missing, broken or without a\n"
         "ProjectorCamera, 2 bad command line, 3 no X display.\n";
}
}  // namespace rviz_projector
