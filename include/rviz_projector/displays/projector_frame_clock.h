// When the projector renders, one part of ProjectorCameraDisplay: a single-shot precise timer at
// FramePacer's deadlines (the Frame rate limit, or the output screen's refresh when lower), an
// early frame when something shown changed and the limit allows it, and the rate of frames
// actually rendered (FrameRateMeter) for health(). The display renders at each tick() and says
// how many frames it has rendered so far.
#pragma once

#ifndef Q_MOC_RUN
#include <cstdint>

#include <QElapsedTimer>
#include <QObject>
#include <QTimer>

#include "rviz_projector/core/frame_pacer.h"
#include "rviz_projector/core/frame_rate_meter.h"
#endif

namespace rviz_projector
{
class ProjectorFrameClock : public QObject
{
  Q_OBJECT
public:
  ProjectorFrameClock();

  /// Frames per second: the lower of `limit` and `refresh` (Hz; 0 when unknown).
  void setRate(double limit, double refresh);
  /// Seconds between frames.
  double period() const { return pacer_.period(); }
  /// A tick at once, then one at each deadline (after each frameDone()) until stop().
  void start();
  void stop();
  /// Waiting for the next deadline.
  bool isWaiting() const { return timer_.isActive(); }
  /// The tick's work is done; `frames_rendered` counts all frames rendered so far. The next tick
  /// is scheduled at the next deadline when `next`.
  void frameDone(std::uint64_t frames_rendered, bool next);
  /// Something shown changed: a tick now rather than at the next deadline, unless a frame went out
  /// less than a period ago (the limit holds: an early frame only replaces a deadline that would
  /// have rendered nothing). Returns whether it ticks now.
  bool requestEarlyFrame();

  /// Seconds since construction (monotonic).
  double now() const { return static_cast<double>(clock_.nsecsElapsed()) * 1e-9; }
  /// Frames rendered per second recently (FrameRateMeter).
  double frameRate() const { return meter_.rate(now()); }
  /// Seconds since a frame was last rendered; < 0 before the first.
  double sinceLastFrame() const { return meter_.sinceLastFrame(now()); }

Q_SIGNALS:
  /// Render now (if anything changed), then call frameDone().
  void tick();

private:
  QTimer timer_;
  QElapsedTimer clock_;
  FramePacer pacer_;
  FrameRateMeter meter_;
};
}  // namespace rviz_projector
