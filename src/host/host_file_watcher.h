// projector_host --watch: calls back when the config file changed. Editors often save by writing a
// new file and renaming it over the old one, which ends a plain file watch: the folder is watched
// too, and the file is watched again whenever it exists. Changes within a short quiet period are
// reported once, and only when the file's content differs from the last one reported.
#pragma once

#ifndef Q_MOC_RUN
#include <functional>

#include <QByteArray>
#include <QFileSystemWatcher>
#include <QObject>
#include <QString>
#include <QTimer>
#endif

namespace rviz_projector
{
class HostFileWatcher : public QObject
{
  Q_OBJECT
public:
  /// `changed` runs on the Qt thread, `quiet_ms` after the last change seen.
  HostFileWatcher(const QString& path, std::function<void()> changed, int quiet_ms = 300);

private Q_SLOTS:
  void onChange();
  void onQuiet();

private:
  void watchFile();

  QString path_;
  std::function<void()> changed_;
  QFileSystemWatcher watcher_;
  QTimer quiet_;
  QByteArray last_content_;  ///< SHA-1 of the file as last reported (or at start)
};
}  // namespace rviz_projector
