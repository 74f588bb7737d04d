// projector_host: the projector output of a .rviz config without rviz's GUI, for the robot's own
// computer (README, "Running on the robot").
//   rosrun rviz_projector projector_host [--watch] CONFIG.rviz
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sys/socket.h>
#include <unistd.h>

#include <QApplication>
#include <QSocketNotifier>
#include <QTimer>
#include <ros/ros.h>

#include "rviz_projector/displays/render_policy.h"
#include "host_diagnostics.h"
#include "host_file_watcher.h"
#include "host_options.h"
#include "host_reload_service.h"
#include "host_session.h"
#include "x_display_check.h"

namespace
{
int signal_pipe[2] = {-1, -1};

void onSignal(int signal_number)
{
  const char byte = static_cast<char>(signal_number);
  // Only async-signal-safe calls here: the Qt thread reads the pipe and quits.
  [[maybe_unused]] const ssize_t written = write(signal_pipe[1], &byte, 1);
}

void installSignalHandlers()
{
  if (socketpair(AF_UNIX, SOCK_STREAM, 0, signal_pipe) != 0)
  {
    return;
  }
  struct sigaction action = {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  sigaction(SIGHUP, &action, nullptr);
}

void logLoad(const rviz_projector::HostLoadResult& result)
{
  if (result.ok)
  {
    ROS_INFO("%s", result.message.c_str());
  }
  else
  {
    ROS_ERROR("%s", result.message.c_str());
  }
  for (const std::string& warning : result.warnings)
  {
    ROS_ERROR("%s", warning.c_str());
  }
}
}  // namespace

int main(int argc, char** argv)
{
  using namespace rviz_projector;
  // Our own SIGINT/SIGTERM handling: both end the Qt event loop, which closes the windows.
  ros::init(argc, argv, "projector_host", ros::init_options::NoSigintHandler);
  std::vector<std::string> args;
  ros::removeROSArgs(argc, argv, args);
  args.erase(args.begin());
  const HostOptionsResult parsed = parseHostOptions(args);
  if (parsed.help)
  {
    std::cout << hostUsage();
    return kHostExitOk;
  }
  if (!parsed.error.empty())
  {
    std::cerr << "projector_host: " << parsed.error << "\n\n" << hostUsage();
    return kHostExitUsage;
  }
  const std::string x_problem = xDisplayProblem();
  if (!x_problem.empty())
  {
    std::cerr << "projector_host: " << x_problem << "\n";
    return kHostExitNoDisplay;
  }

  installSignalHandlers();
  QApplication app(argc, argv);
  logXErrors();  // after Qt, which installs a handler of its own that drops them
  app.setQuitOnLastWindowClosed(false);  // windows come and go on reload; the host runs until told
  QSocketNotifier signals(signal_pipe[0], QSocketNotifier::Read);
  QObject::connect(&signals, &QSocketNotifier::activated, &app, [] {
    char byte = 0;
    [[maybe_unused]] const ssize_t got = read(signal_pipe[0], &byte, 1);
    QApplication::quit();
  });
  // rosnode kill / a master's shutdown request.
  QTimer ros_watch;
  QObject::connect(&ros_watch, &QTimer::timeout, &app, [] {
    if (!ros::ok())
    {
      QApplication::quit();
    }
  });
  ros_watch.start(100);

  // The displays, created by pluginlib, take the process's policy and give it to their parts.
  setProcessRenderPolicy(RenderPolicy::projectorHost(parsed.options.keep_alive));
  const QString config = QString::fromStdString(parsed.options.config);
  int status = kHostExitOk;
  {
    HostSession session(config, parsed.options.all_displays);
    const HostLoadResult first = session.start();
    logLoad(first);
    if (!first.ok)
    {
      std::cerr << "projector_host: " << first.message << "\n";
      status = kHostExitBadConfig;
    }
    else
    {
      HostDiagnostics diagnostics(session);
      diagnostics.setLastLoad(first);
      auto reload = [&session, &diagnostics] {
        const HostLoadResult result = session.reload();
        logLoad(result);
        diagnostics.setLastLoad(result);
        return result;
      };
      HostReloadService service(reload);
      std::unique_ptr<HostFileWatcher> watcher;
      if (parsed.options.watch)
      {
        watcher = std::make_unique<HostFileWatcher>(config, [reload] { reload(); });
      }
      QApplication::exec();
      ROS_INFO("projector_host: stopping");
    }
  }  // the session deletes the displays: the projector windows close, the floor goes dark
  ros::shutdown();
  return status;
}
