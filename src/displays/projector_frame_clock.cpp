#include "rviz_projector/displays/projector_frame_clock.h"

#include <cmath>

namespace rviz_projector
{
ProjectorFrameClock::ProjectorFrameClock()
{
  timer_.setSingleShot(true);
  timer_.setTimerType(Qt::PreciseTimer);
  connect(&timer_, &QTimer::timeout, this, &ProjectorFrameClock::tick);
  clock_.start();
}

void ProjectorFrameClock::setRate(double limit, double refresh)
{
  pacer_.setPeriod(1.0 / FramePacer::rate(limit, refresh));
}

void ProjectorFrameClock::start()
{
  timer_.start(0);
}

void ProjectorFrameClock::stop()
{
  timer_.stop();
}

void ProjectorFrameClock::frameDone(std::uint64_t frames_rendered, bool next)
{
  meter_.sample(now(), frames_rendered);
  if (next)
  {
    const double delay = pacer_.tick(now());
    timer_.start(static_cast<int>(std::ceil(delay * 1000.0)));
  }
}

bool ProjectorFrameClock::requestEarlyFrame()
{
  if (!timer_.isActive() || meter_.sinceLastFrame(now()) < pacer_.period())
  {
    return false;
  }
  timer_.start(0);
  return true;
}
}  // namespace rviz_projector
