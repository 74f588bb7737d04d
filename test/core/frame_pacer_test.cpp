// FramePacer: a millisecond timer paced by it delivers the asked rate on average, with no bursts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rviz_projector/core/frame_pacer.h"

using rviz_projector::FramePacer;

namespace
{
/// Runs a Qt-like millisecond single-shot timer for `seconds`: each delay is rounded up to whole
/// milliseconds and the wake-up comes `late` seconds after that. Returns the number of ticks.
int ticksIn(double seconds, double period, double late)
{
  FramePacer pacer;
  pacer.setPeriod(period);
  double now = 0.0;
  int ticks = 0;
  while (now < seconds)
  {
    ++ticks;
    const double delay = pacer.tick(now);
    now += std::ceil(delay * 1000.0 - 1e-9) / 1000.0 + late;
  }
  return ticks;
}
}  // namespace

TEST(FramePacer, RateIsTheLowerOfLimitAndRefresh)
{
  EXPECT_DOUBLE_EQ(FramePacer::rate(60, 0), 60.0);       // refresh unknown
  EXPECT_DOUBLE_EQ(FramePacer::rate(60, 75), 60.0);
  EXPECT_DOUBLE_EQ(FramePacer::rate(120, 59.94), 59.94); // the projector's refresh wins
  EXPECT_DOUBLE_EQ(FramePacer::rate(30, 60), 30.0);
  EXPECT_DOUBLE_EQ(FramePacer::rate(std::numeric_limits<double>::quiet_NaN(), 0), 60.0);
  EXPECT_DOUBLE_EQ(FramePacer::rate(0, 0), 60.0);
}

TEST(FramePacer, MillisecondTimerDeliversExactlySixtyFramesPerSecond)
{
  // 10 s at 60 Hz: 600 frames (a plain 16 ms timer gives 625, 17 ms gives 588).
  EXPECT_NEAR(ticksIn(10.0, 1.0 / 60.0, 0.0), 600, 1);
  EXPECT_NEAR(ticksIn(10.0, 1.0 / 60.0, 0.0003), 600, 1);  // wake-ups 0.3 ms late
  EXPECT_NEAR(ticksIn(10.0, 1.0 / 59.94, 0.0002), 599, 1);
  EXPECT_NEAR(ticksIn(10.0, 1.0 / 144.0, 0.0), 1440, 1);
}

TEST(FramePacer, DelayNeverExceedsAPeriodAndLateTicksDoNotBurst)
{
  FramePacer pacer;
  pacer.setPeriod(0.02);
  EXPECT_NEAR(pacer.tick(1.0), 0.02, 1e-12);    // first tick: one period
  EXPECT_NEAR(pacer.tick(1.025), 0.015, 1e-12);  // 5 ms late: the deadline stays on the grid
  // Stalled for 10 periods (rendering blocked): the next frame comes one period later, not at once
  // ten times over.
  EXPECT_NEAR(pacer.tick(1.3), 0.02, 1e-12);
  EXPECT_NEAR(pacer.tick(1.32), 0.02, 1e-12);
  for (double now = 2.0; now < 3.0; now += 0.0137)
  {
    const double d = pacer.tick(now);
    EXPECT_GE(d, 0.0);
    EXPECT_LE(d, 0.02);
  }
}

TEST(FramePacer, BadPeriodFallsBackToSixtyHertz)
{
  FramePacer pacer;
  pacer.setPeriod(0.0);
  EXPECT_NEAR(pacer.period(), 1.0 / 60.0, 1e-12);
  pacer.setPeriod(std::numeric_limits<double>::infinity());
  EXPECT_NEAR(pacer.period(), 1.0 / 60.0, 1e-12);
  const double d = pacer.tick(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(d >= 0.0 && d <= pacer.period()) << d;
}
