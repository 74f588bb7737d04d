// dataAge/isStale and FrameRateMeter: the numbers behind "Path timeout", "TF timeout" and the
// ProjectorCamera's health(), checked against hand-computed values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rviz_projector/core/data_age.h"
#include "rviz_projector/core/frame_rate_meter.h"

using rviz_projector::dataAge;
using rviz_projector::FrameRateMeter;
using rviz_projector::isStale;

TEST(DataAge, AgeIsNowMinusStamp)
{
  EXPECT_DOUBLE_EQ(dataAge(100.0, 102.5), 2.5);
  EXPECT_DOUBLE_EQ(dataAge(1.7e9, 1.7e9 + 0.25), 0.25);
}

TEST(DataAge, StaticStampIsNeverOld)
{
  EXPECT_EQ(dataAge(0.0, 1.7e9), 0.0);
}

TEST(DataAge, FutureStampsAndNonFiniteTimesAreZeroOld)
{
  EXPECT_EQ(dataAge(105.0, 100.0), 0.0);
  EXPECT_EQ(dataAge(std::nan(""), 100.0), 0.0);
  EXPECT_EQ(dataAge(100.0, std::numeric_limits<double>::infinity()), 0.0);
}

TEST(DataAge, StaleOnlyPastAPositiveTimeout)
{
  EXPECT_TRUE(isStale(1.5, 1.0));
  EXPECT_FALSE(isStale(1.0, 1.0));  // exactly the timeout: still shown
  EXPECT_FALSE(isStale(0.5, 1.0));
  EXPECT_FALSE(isStale(1e9, 0.0));   // 0: never
  EXPECT_FALSE(isStale(1e9, -3.0));  // negative: never
  EXPECT_FALSE(isStale(1e9, std::nan("")));
  EXPECT_FALSE(isStale(std::nan(""), 1.0));  // no data is not stale data
}

TEST(FrameRateMeter, NoRateBeforeTwoSamples)
{
  FrameRateMeter meter(2.0);
  EXPECT_EQ(meter.rate(0.0), 0.0);
  EXPECT_LT(meter.sinceLastFrame(0.0), 0.0);
  meter.sample(0.0, 0);
  EXPECT_EQ(meter.rate(1.0), 0.0);
  EXPECT_LT(meter.sinceLastFrame(1.0), 0.0);  // the count never grew
}

TEST(FrameRateMeter, SteadyRateOverTheWindow)
{
  // 30 frames per second sampled at 60 Hz (every other tick renders), for 5 s.
  FrameRateMeter meter(2.0);
  std::uint64_t total = 0;
  for (int tick = 0; tick <= 300; ++tick)
  {
    if (tick % 2 == 0 && tick > 0)
    {
      ++total;
    }
    meter.sample(tick / 60.0, total);
  }
  EXPECT_NEAR(meter.rate(5.0), 30.0, 0.01);
  EXPECT_NEAR(meter.sinceLastFrame(5.0), 0.0, 1e-9);  // tick 300 rendered
}

TEST(FrameRateMeter, ShortHistoryMeasuresOverItsLength)
{
  FrameRateMeter meter(2.0);
  meter.sample(10.0, 0);
  meter.sample(10.5, 5);  // 5 frames in 0.5 s
  EXPECT_NEAR(meter.rate(10.5), 10.0, 1e-9);
}

TEST(FrameRateMeter, RateFallsWhenFramesStop)
{
  FrameRateMeter meter(2.0);
  for (int i = 0; i <= 20; ++i)
  {
    meter.sample(i * 0.1, static_cast<std::uint64_t>(i));  // 10 frames/s for 2 s
  }
  EXPECT_NEAR(meter.rate(2.0), 10.0, 1e-9);
  // Samples go on, but no frame is rendered from t = 2 s on.
  for (int i = 21; i <= 30; ++i)
  {
    meter.sample(i * 0.1, 20);
  }
  // Window [1, 3]: 10 frames (from t = 1 to 2) over 2 s.
  EXPECT_NEAR(meter.rate(3.0), 5.0, 1e-9);
  EXPECT_NEAR(meter.sinceLastFrame(3.0), 1.0, 1e-9);
  for (int i = 31; i <= 60; ++i)
  {
    meter.sample(i * 0.1, 20);
  }
  EXPECT_NEAR(meter.rate(6.0), 0.0, 1e-9);
  EXPECT_NEAR(meter.sinceLastFrame(6.0), 4.0, 1e-9);
}

TEST(FrameRateMeter, TimeGoingBackIsIgnored)
{
  FrameRateMeter meter(2.0);
  meter.sample(5.0, 0);
  meter.sample(6.0, 10);
  meter.sample(4.0, 1000);  // ignored
  EXPECT_NEAR(meter.rate(6.0), 10.0, 1e-9);
}

TEST(FrameRateMeter, SamplingFasterThanTheRingHoldsMeasuresTheNewestSamples)
{
  // 2000 samples per second for 3 s: more than kCapacity in the 2 s window. The oldest go first;
  // 100 frames/s (one frame every 20 samples) is still measured over what is kept.
  FrameRateMeter meter(2.0);
  std::uint64_t total = 0;
  for (int i = 0; i <= 6000; ++i)
  {
    if (i > 0 && i % 20 == 0)
    {
      ++total;
    }
    meter.sample(i / 2000.0, total);
  }
  // kCapacity samples span 0.51 s: a frame more or less at its ends is 2 frames/s.
  EXPECT_NEAR(meter.rate(3.0), 100.0, 4.0);
  EXPECT_NEAR(meter.sinceLastFrame(3.0), 0.0, 1e-9);
  // Then one sample a second: the full ring empties to the window as before.
  for (int s = 4; s <= 10; ++s)
  {
    meter.sample(s, total + static_cast<std::uint64_t>(s - 3) * 10);
  }
  EXPECT_NEAR(meter.rate(10.0), 10.0, 1e-9);
}
