// The statuses a display shows, remembered so that only changes reach rviz: one part of
// ProjectorCameraDisplay, which evaluates its statuses every frame (each rviz setStatus call posts
// an event and repaints the Displays panel). It answers whether a call is a change; the display
// forwards only those to rviz::Display.
#pragma once

#include <map>

#include <QString>

namespace rviz_projector
{
class StatusCache
{
public:
  /// Remembers `level` and `text` under `name`. Returns true when they differ from what is shown
  /// (a new name, another level or another text): the caller shows them.
  bool set(int level, const QString& name, const QString& text);
  /// Forgets `name`. Returns true when it was shown: the caller deletes it.
  bool remove(const QString& name);
  /// Forgets every status (rviz's Reset cleared them).
  void clear() { statuses_.clear(); }
  /// Whether a status `name` is shown.
  bool has(const QString& name) const { return statuses_.count(name) > 0; }
  /// The text shown under `name` (empty when none).
  QString text(const QString& name) const;

private:
  struct Shown
  {
    int level;
    QString text;
  };
  std::map<QString, Shown> statuses_;
};
}  // namespace rviz_projector
