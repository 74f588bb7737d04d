// Tells the projector views of this process at once that something they may show changed, so a
// frame can leave before the next paced deadline: path-to-photon latency without a faster timer.
#pragma once

#ifndef Q_MOC_RUN
#include <QObject>
#endif

namespace rviz_projector
{
/**
 * One process-wide QObject on the Qt (GUI) thread. notify() bumps ProjectionChangeCounter (the
 * record every projector compares at each frame, projection_change_counter.h) and emits changed().
 * ProjectorCameraDisplay listens with a queued connection: it only restarts its frame timer, it
 * never renders inside the notifier's caller (another display's code).
 */
class ProjectionChangeNotifier : public QObject
{
  Q_OBJECT
public:
  static ProjectionChangeNotifier& instance();
  /// Something drawn by an rviz_projector display changed. Qt thread only.
  static void notify();

Q_SIGNALS:
  void changed();
};
}  // namespace rviz_projector
