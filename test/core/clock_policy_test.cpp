// ClockPolicy (issue 23): the rate of ROS time against steady time, backward jumps as epochs, and
// steady delays in ROS seconds. Expected values by hand from the readings fed in.
#include <gtest/gtest.h>

#include <cmath>

#include "rviz_projector/core/clock_policy.h"
#include "rviz_projector/core/data_age.h"

using rviz_projector::ClockPolicy;
using rviz_projector::EpochWatch;

namespace
{
/// Feeds readings every `step` steady seconds for `span` seconds, ROS time advancing `rate` times as fast.
void run(ClockPolicy& clock, double& ros, double& steady, double rate, double span, double step = 1.0 / 60.0)
{
  for (double t = 0.0; t < span; t += step)
  {
    ros += rate * step;
    steady += step;
    clock.update(ros, steady);
  }
}
}  // namespace

TEST(ClockPolicy, RateIsOneUntilMeasuredAndFollowsTheBagRate)
{
  ClockPolicy clock;
  EXPECT_DOUBLE_EQ(clock.rate(), 1.0);
  double ros = 1000.0, steady = 5.0;
  clock.update(ros, steady);
  run(clock, ros, steady, 0.5, 2.0);  // rosbag play -r 0.5
  EXPECT_NEAR(clock.rate(), 0.5, 1e-6);
  EXPECT_NEAR(clock.rosSeconds(0.020), 0.010, 1e-8) << "20 ms of photon delay is 10 ms of ROS time at half rate";
  run(clock, ros, steady, 2.0, 2.0);  // -r 2
  EXPECT_NEAR(clock.rate(), 2.0, 1e-6);
  run(clock, ros, steady, 0.0, 2.0);  // paused
  EXPECT_NEAR(clock.rate(), 0.0, 1e-9);
  EXPECT_EQ(clock.epoch(), 0u) << "no jump in any of these";
  EXPECT_DOUBLE_EQ(clock.rosNow(), ros);
  EXPECT_DOUBLE_EQ(clock.steadyNow(), steady);
}

TEST(ClockPolicy, BackwardJumpStartsANewEpochOnceAndKeepsTheRate)
{
  ClockPolicy clock;
  double ros = 1000.0, steady = 0.0;
  clock.update(ros, steady);
  run(clock, ros, steady, 0.5, 2.0);
  EpochWatch follower;
  EXPECT_FALSE(follower.changed(clock)) << "the first look is no change";
  EXPECT_FALSE(clock.sinceJump() < ClockPolicy::kJumpGrace) << "no jump yet";
  // Loop of the bag: back to 1000 s.
  EXPECT_TRUE(clock.update(1000.0, steady + 0.01));
  EXPECT_EQ(clock.epoch(), 1u);
  EXPECT_TRUE(follower.changed(clock));
  EXPECT_FALSE(follower.changed(clock)) << "one jump is one change";
  EXPECT_NEAR(clock.rate(), 0.5, 1e-6) << "the bag's rate is the same after the loop";
  EXPECT_NEAR(clock.sinceJump(), 0.0, 1e-12);
  clock.update(1000.3, steady + 0.31);
  EXPECT_NEAR(clock.sinceJump(), 0.30, 1e-9) << "steady seconds since the jump";
  // Rounding of a simulated clock (under the tolerance) is no jump.
  EXPECT_FALSE(clock.update(1000.3 - 0.5 * ClockPolicy::kBackwardTolerance, steady + 0.32));
  EXPECT_EQ(clock.epoch(), 1u);
}

TEST(ClockPolicy, ForwardJumpsAndBadReadingsDoNotBecomeARate)
{
  ClockPolicy clock;
  double ros = 1000.0, steady = 0.0;
  clock.update(ros, steady);
  run(clock, ros, steady, 1.0, 1.0);
  ASSERT_NEAR(clock.rate(), 1.0, 1e-6);
  clock.update(ros + 3600.0, steady + 0.6);  // an hour skipped in 0.6 s: a jump, not 6000x
  EXPECT_NEAR(clock.rate(), 1.0, 1e-6);
  EXPECT_FALSE(clock.update(std::nan(""), steady + 1.0));
  EXPECT_FALSE(clock.update(ros, INFINITY));
  EXPECT_TRUE(std::isfinite(clock.rate()));
  clock.fixRate(0.25);
  EXPECT_DOUBLE_EQ(clock.rate(), 0.25);
  EXPECT_DOUBLE_EQ(clock.rosSeconds(0.1), 0.025);
  clock.fixRate(std::nan(""));
  EXPECT_NEAR(clock.rate(), 1.0, 1e-6) << "measured again";
}

TEST(DataAge, StampsFromBeforeABackwardJumpAreFromTheFuture)
{
  using rviz_projector::isFromTheFuture;
  EXPECT_TRUE(isFromTheFuture(200.0, 100.0, 1.0));
  EXPECT_FALSE(isFromTheFuture(100.5, 100.0, 1.0)) << "skew within the timeout";
  EXPECT_FALSE(isFromTheFuture(0.0, 100.0, 1.0)) << "static";
  EXPECT_FALSE(isFromTheFuture(200.0, 100.0, 0.0)) << "timeout 0: never";
  EXPECT_FALSE(isFromTheFuture(std::nan(""), 100.0, 1.0));
}

TEST(ClockPolicy, ASimulatedClockStartingOpensTheTfGraceAsAJumpBackDoes)
{
  // Under /use_sim_time ROS time reads 0 until the first /clock; the bag's tf follows it.
  ClockPolicy clock;
  clock.update(0.0, 10.0);
  clock.update(0.0, 10.5);
  EXPECT_FALSE(clock.justStartedOrJumpedBack()) << "no time yet, nothing started";
  clock.update(1700000000.0, 11.0);
  EXPECT_EQ(clock.epoch(), 0u) << "time starting is no backward jump: nothing to forget";
  EXPECT_NEAR(clock.sinceTimeStarted(), 0.0, 1e-12);
  EXPECT_TRUE(clock.justStartedOrJumpedBack());
  clock.update(1700000000.9, 11.9);
  EXPECT_TRUE(clock.justStartedOrJumpedBack()) << "0.9 s after the start";
  clock.update(1700000001.1, 12.1);
  EXPECT_FALSE(clock.justStartedOrJumpedBack()) << "1.1 s after the start: tf missing now is an error";

  // A wall clock (never zero) never started in this sense.
  ClockPolicy wall;
  wall.update(1700000000.0, 5.0);
  wall.update(1700000000.1, 5.1);
  EXPECT_FALSE(wall.justStartedOrJumpedBack());
  EXPECT_TRUE(std::isinf(wall.sinceTimeStarted()));
}

TEST(ClockPolicy, AMessageBelongsToTheTimelineOfRosNowUnlessStampedAfterIt)
{
  // A bag of 100..110 s looping: ROS time jumps from 110 back to 100.
  EXPECT_TRUE(ClockPolicy::inCurrentTimeline(100.05, 100.0)) << "replayed just after the jump, clock read late";
  EXPECT_TRUE(ClockPolicy::inCurrentTimeline(100.25, 100.0)) << "the slack's edge";
  EXPECT_FALSE(ClockPolicy::inCurrentTimeline(100.26, 100.0));
  EXPECT_FALSE(ClockPolicy::inCurrentTimeline(109.6, 100.0)) << "the last plan before the jump";
  EXPECT_TRUE(ClockPolicy::inCurrentTimeline(50.0, 100.0)) << "an old message is of this timeline";
  EXPECT_TRUE(ClockPolicy::inCurrentTimeline(0.0, 100.0)) << "unstamped";
  EXPECT_FALSE(ClockPolicy::inCurrentTimeline(std::nan(""), 100.0)) << "no stamp to trust";
}
