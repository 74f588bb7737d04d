#include "rviz_projector/displays/projection_change_notifier.h"

#include "rviz_projector/displays/projection_change_counter.h"

namespace rviz_projector
{
ProjectionChangeNotifier& ProjectionChangeNotifier::instance()
{
  static ProjectionChangeNotifier notifier;
  return notifier;
}

void ProjectionChangeNotifier::notify()
{
  ProjectionChangeCounter::bump();
  Q_EMIT instance().changed();
}
}  // namespace rviz_projector
