// projector_host's diagnostics on /diagnostics (diagnostic_updater): one status per ProjectorCamera
// (output frame rate, time since the last frame, tf and CameraInfo age, screen, and the statuses
// rviz shows for that display), one for all other displays' statuses, one for the config (last
// load or reload). Rebuilt whenever the session loads a configuration.
#pragma once

#ifndef Q_MOC_RUN
#include <string>
#include <vector>

#include <QObject>
#include <QTimer>
#include <diagnostic_updater/diagnostic_updater.h>

#include "rviz_projector/core/clock_policy.h"
#endif

namespace rviz_projector
{
class HostSession;
struct HostLoadResult;

class HostDiagnostics : public QObject
{
  Q_OBJECT
public:
  explicit HostDiagnostics(HostSession& session);
  ~HostDiagnostics() override;

  /// The outcome of the last load or reload, for the config status.
  void setLastLoad(const HostLoadResult& result);

private Q_SLOTS:
  void rebuild();

private:
  void configStatus(diagnostic_updater::DiagnosticStatusWrapper& status);
  void displaysStatus(diagnostic_updater::DiagnosticStatusWrapper& status);

  HostSession& session_;
  diagnostic_updater::Updater updater_;
  std::vector<std::string> task_names_;
  QTimer timer_;
  EpochWatch epoch_;  ///< of RosClock::shared(): a backward jump of ROS time publishes at once
  bool last_ok_ = true;
  std::string last_message_;
  std::vector<std::string> last_warnings_;
};
}  // namespace rviz_projector
