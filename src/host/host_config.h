// Reads and checks a .rviz config for projector_host before anything of the running configuration
// is touched: the file, its YAML, the display classes (pluginlib) and the types of the property
// values, and that it holds a ProjectorCamera. The host loads only a config that passed (reload:
// a broken file leaves the last good configuration running).
#pragma once

#ifndef Q_MOC_RUN
#include <string>
#include <vector>

#include <QString>
#include <rviz/config.h>
#endif

namespace rviz
{
class DisplayFactory;
}

namespace rviz_projector
{
struct HostConfigDisplay
{
  QString class_id;
  QString name;
  bool enabled = true;
  bool available = true;  ///< the class is installed (pluginlib knows it)
};

struct HostConfigCheck
{
  /// Empty: the config can be loaded. Else one sentence naming the file and what is wrong.
  std::string error;
  /// Problems that do not stop a load: each names a display that will show an error instead.
  std::vector<std::string> warnings;
  /// Every display of the file, groups included, in file order.
  std::vector<HostConfigDisplay> displays;
  int projectors = 0;  ///< enabled or not
  /// The "Visualization Manager" part, ready for VisualizationManager::load().
  rviz::Config manager_config;
};

/// How strict a check is.
enum class MissingPlugin
{
  Warn,   ///< start-up: the display is skipped with an error (rviz's FailedDisplay), the rest runs
  Refuse  ///< reload: the file is refused, the last good configuration keeps running
};

/// Reads `path` and checks it. `factory` is rviz's display factory (pluginlib); it also builds a
/// throw-away instance of each display class (never initialised) to learn its property types.
HostConfigCheck checkHostConfig(const QString& path, rviz::DisplayFactory& factory, MissingPlugin missing);
}  // namespace rviz_projector
