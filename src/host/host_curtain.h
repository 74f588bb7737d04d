// A black cover over the projector windows while projector_host reloads its config: the old
// windows close and the new ones open underneath, so the floor never shows the desktop or an
// unpainted (white) window in between. Taken away once every new projector drew a frame.
#pragma once

#ifndef Q_MOC_RUN
#include <functional>
#include <memory>
#include <vector>

#include <QElapsedTimer>
#include <QObject>
#include <QRect>
#include <QTimer>
#endif

class QWidget;

namespace rviz_projector
{
class HostCurtain : public QObject
{
  Q_OBJECT
public:
  HostCurtain();
  ~HostCurtain() override;

  /// Shows a black, frameless window over each of these screen rectangles (the projector windows
  /// about to be replaced), above them, and returns when they are mapped.
  void cover(const std::vector<QRect>& areas);
  /// Takes the cover away as soon as `ready()` is true (the new projectors drew), or after
  /// `timeout_s` at the latest.
  void uncoverWhen(std::function<bool()> ready, double timeout_s);
  bool covering() const { return !windows_.empty(); }

private Q_SLOTS:
  void poll();

private:
  void uncover();

  std::vector<std::unique_ptr<QWidget>> windows_;
  std::function<bool()> ready_;
  QTimer poll_timer_;
  QElapsedTimer since_;
  double timeout_ms_ = 0.0;
};
}  // namespace rviz_projector
