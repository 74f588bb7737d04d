#include "host_file_watcher.h"

#include <QCryptographicHash>
#include <QFile>
#include <QFileInfo>

namespace rviz_projector
{
namespace
{
QByteArray contentHash(const QString& path)
{
  QFile file(path);
  if (!file.open(QIODevice::ReadOnly))
  {
    return QByteArray();
  }
  return QCryptographicHash::hash(file.readAll(), QCryptographicHash::Sha1);
}
}  // namespace

HostFileWatcher::HostFileWatcher(const QString& path, std::function<void()> changed, int quiet_ms)
  : path_(QFileInfo(path).absoluteFilePath()), changed_(std::move(changed))
{
  quiet_.setSingleShot(true);
  quiet_.setInterval(quiet_ms);
  connect(&quiet_, &QTimer::timeout, this, &HostFileWatcher::onQuiet);
  connect(&watcher_, &QFileSystemWatcher::fileChanged, this, &HostFileWatcher::onChange);
  connect(&watcher_, &QFileSystemWatcher::directoryChanged, this, &HostFileWatcher::onChange);
  watcher_.addPath(QFileInfo(path_).absolutePath());
  watchFile();
  last_content_ = contentHash(path_);
}

void HostFileWatcher::watchFile()
{
  if (QFileInfo::exists(path_) && !watcher_.files().contains(path_))
  {
    watcher_.addPath(path_);
  }
}

void HostFileWatcher::onChange()
{
  quiet_.start();  // restarts: one report after the last of a burst of changes
}

void HostFileWatcher::onQuiet()
{
  watchFile();
  // Other files of the folder change too, and editors touch files without changing them.
  const QByteArray content = contentHash(path_);
  if (!content.isEmpty() && content != last_content_)
  {
    last_content_ = content;
    changed_();
  }
}
}  // namespace rviz_projector
