// projector_host's one rviz: a VisualizationManager with the displays of a .rviz config, without
// rviz's main window and without rendering a main view (its RenderPanel is never shown and its
// render window is inactive). Loads the config at start and on reload; a config that fails
// checkHostConfig() is refused and the running one stays. Displays that no ProjectorCamera shows
// (none ticks them in its Visibility) are not run ("parked": disabled after each load), unless the
// session runs all displays: nothing but the projectors is shown here, so they would only cost CPU
// (rviz's TF display alone was 6.6 % of the demo's main thread; doc/dev/performance.md).
#pragma once

#ifndef Q_MOC_RUN
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <QObject>
#include <QPointer>
#include <QString>
#endif

namespace Ogre
{
class RenderTargetListener;
}

namespace rviz
{
class Display;
class RenderPanel;
class VisualizationManager;
}  // namespace rviz

namespace rviz_projector
{
class HostCurtain;
class ProjectorCameraDisplay;

/// What the host's diagnostics say of a parked display (HostSession::parked).
constexpr const char* kParkedDisplay = "not run: no ProjectorCamera shows it (--all-displays runs it)";

struct HostLoadResult
{
  bool ok = false;
  std::string message;                ///< what was loaded, or why not
  std::vector<std::string> warnings;  ///< displays skipped (plugin missing)
};

class HostSession : public QObject
{
  Q_OBJECT
public:
  /// `all_displays`: run every enabled display, also those no ProjectorCamera shows.
  HostSession(const QString& config_path, bool all_displays);
  ~HostSession() override;

  /// First load. Not ok: the host has nothing to show and exits (kHostExitBadConfig).
  HostLoadResult start();
  /// Re-reads the file; a broken file is refused (the last good configuration keeps running).
  /// Qt thread only. The old displays are deleted: callers hold no Display pointer across it.
  HostLoadResult reload();

  const QString& configPath() const { return path_; }
  rviz::VisualizationManager* manager() const { return manager_; }
  /// Every ProjectorCamera of the running configuration (groups included).
  std::vector<ProjectorCameraDisplay*> projectors() const;
  /// Every display of the running configuration (groups included, groups themselves too).
  std::vector<rviz::Display*> displays() const;
  /// Number of loads that changed the running configuration (start included).
  int generation() const { return generation_; }
  /// Frames rendered into rviz's main view since start: 0 is the point of the host.
  std::uint64_t mainViewFrames() const;
  /// Whether the last load parked `display` (enabled in the config, shown by no ProjectorCamera).
  bool parked(const rviz::Display* display) const;

Q_SIGNALS:
  /// The displays were replaced (start or a successful reload).
  void loaded();

private:
  HostLoadResult load(bool first);
  /// Disables the enabled displays that no ProjectorCamera shows (into parked_).
  void parkUnshownDisplays();

  QString path_;
  rviz::RenderPanel* panel_ = nullptr;
  rviz::VisualizationManager* manager_ = nullptr;
  std::unique_ptr<HostCurtain> curtain_;
  std::unique_ptr<Ogre::RenderTargetListener> main_view_counter_;
  int generation_ = 0;
  bool all_displays_ = false;
  std::vector<const rviz::Display*> parked_;  ///< of the running configuration
};
}  // namespace rviz_projector
