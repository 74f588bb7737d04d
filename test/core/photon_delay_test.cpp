// PhotonDelay (issue 14): the smoothed time from a pose lookup to the middle of the frame's time on
// screen, render delay + hold / 2. Expected values are exponential moving averages computed by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rviz_projector/core/photon_delay.h"

using rviz_projector::PhotonDelay;

namespace
{
const double kPeriod = 1.0 / 60.0;
const double kT0 = 5000.0;  // a monotonic clock, far from 0

/// n frames from `start`, one per period, each handed to the screen `render` s after its lookup.
/// Returns the next frame's lookup time.
double frames(PhotonDelay& d, double start, int n, double render, double spacing = kPeriod)
{
  for (int i = 0; i < n; ++i)
  {
    d.frame(start + i * spacing, start + i * spacing + render, kPeriod);
  }
  return start + n * spacing;
}
}  // namespace

TEST(PhotonDelay, BeforeAnyFrame)
{
  const PhotonDelay d;
  EXPECT_EQ(d.renderDelay(), 0.0);
  EXPECT_EQ(d.hold(kPeriod), kPeriod);
  EXPECT_DOUBLE_EQ(d.expected(kPeriod), kPeriod / 2);
  EXPECT_DOUBLE_EQ(d.expected(0.01), 0.005);
}

TEST(PhotonDelay, ConvergesToConstantInputs)
{
  PhotonDelay d;
  frames(d, kT0, 300, 0.012);  // 0.9^300 = 2e-14 of any start left
  EXPECT_NEAR(d.renderDelay(), 0.012, 1e-9);
  EXPECT_NEAR(d.hold(kPeriod), kPeriod, 1e-9);
  EXPECT_NEAR(d.expected(kPeriod), 0.012 + kPeriod / 2, 1e-9);
  // The hold is measured, not the period asked for: frames every 20 ms for a 60 Hz target.
  PhotonDelay slow;
  frames(slow, kT0, 300, 0.005, 0.020);
  EXPECT_NEAR(slow.hold(kPeriod), 0.020, 1e-9);
  EXPECT_NEAR(slow.expected(kPeriod), 0.005 + 0.010, 1e-9);
}

TEST(PhotonDelay, MovingAveragesByHand)
{
  // Smoothing 0.5: the first measurement is taken as it is, then new = (old + measured) / 2.
  PhotonDelay d(0.5);
  d.frame(kT0, kT0 + 0.010, kPeriod);
  EXPECT_NEAR(d.renderDelay(), 0.010, 1e-12);
  EXPECT_EQ(d.hold(kPeriod), kPeriod);  // one frame: no hold yet
  d.frame(kT0 + 0.010, kT0 + 0.030, kPeriod);  // render 20 ms, hold 20 ms
  EXPECT_NEAR(d.renderDelay(), 0.015, 1e-12);
  EXPECT_NEAR(d.hold(kPeriod), 0.020, 1e-12);
  d.frame(kT0 + 0.035, kT0 + 0.040, kPeriod);  // render 5 ms, hold 10 ms
  EXPECT_NEAR(d.renderDelay(), 0.010, 1e-12);
  EXPECT_NEAR(d.hold(kPeriod), 0.015, 1e-12);
  EXPECT_NEAR(d.expected(kPeriod), 0.010 + 0.0075, 1e-12);
  // Smoothing 1: the last measurement.
  PhotonDelay last(1.0);
  last.frame(kT0, kT0 + 0.010, kPeriod);
  last.frame(kT0 + 0.010, kT0 + 0.013, kPeriod);
  EXPECT_NEAR(last.renderDelay(), 0.003, 1e-12);
  EXPECT_NEAR(last.hold(kPeriod), 0.003, 1e-12);
}

TEST(PhotonDelay, GapsAreNotHolds)
{
  // Frames at 60 Hz with pauses of 5 periods (nothing to draw): the hold stays one period.
  PhotonDelay d;
  double t = frames(d, kT0, 50, 0.008);
  for (int i = 0; i < 10; ++i)
  {
    t = frames(d, t + 4 * kPeriod, 20, 0.008);
  }
  EXPECT_NEAR(d.hold(kPeriod), kPeriod, 1e-9);
  EXPECT_NEAR(d.renderDelay(), 0.008, 1e-9);
  // A pause before the second frame ever: still no hold measured.
  PhotonDelay first;
  first.frame(kT0, kT0 + 0.008, kPeriod);
  first.frame(kT0 + 1.0, kT0 + 1.008, kPeriod);
  EXPECT_EQ(first.hold(kPeriod), kPeriod);
  // 1.5 periods between frames is a hold (a late frame): averaged.
  PhotonDelay late(1.0);
  late.frame(kT0, kT0 + 0.008, kPeriod);
  late.frame(kT0 + 1.5 * kPeriod, kT0 + 1.5 * kPeriod + 0.008, kPeriod);
  EXPECT_NEAR(late.hold(kPeriod), 1.5 * kPeriod, 1e-12);
}

TEST(PhotonDelay, ClearForgets)
{
  PhotonDelay d;
  frames(d, kT0, 100, 0.02, 0.030);
  d.clear();
  EXPECT_EQ(d.renderDelay(), 0.0);
  EXPECT_EQ(d.hold(kPeriod), kPeriod);
  EXPECT_DOUBLE_EQ(d.expected(kPeriod), kPeriod / 2);
  // After clear() the first frame is a first frame again: its render delay as it is, no hold
  // measured against the frame before clear().
  d.frame(kT0 + 100 * 0.030 + 0.005, kT0 + 100 * 0.030 + 0.009, kPeriod);
  EXPECT_NEAR(d.renderDelay(), 0.004, 1e-12);
  EXPECT_EQ(d.hold(kPeriod), kPeriod);
}

TEST(PhotonDelay, BadInputLeavesSaneValues)
{
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  PhotonDelay d;
  frames(d, kT0, 100, 0.01);
  const double t = kT0 + 100 * kPeriod;
  d.frame(nan, t, kPeriod);
  d.frame(t, nan, kPeriod);
  d.frame(t, inf, kPeriod);
  d.frame(t, t + 0.01, nan);
  d.frame(t, t + 0.01, -kPeriod);
  d.frame(t + 0.01, t, kPeriod);          // shown before the lookup
  d.frame(t - 1.0, t - 0.99, kPeriod);    // shown before the frame before (clock stepped back)
  EXPECT_TRUE(std::isfinite(d.renderDelay()));
  EXPECT_GE(d.renderDelay(), 0.0);
  EXPECT_TRUE(std::isfinite(d.hold(kPeriod)));
  EXPECT_GT(d.hold(kPeriod), 0.0);
  EXPECT_TRUE(std::isfinite(d.expected(kPeriod)));
  EXPECT_LE(d.expected(kPeriod), 0.01 + kPeriod);
}
