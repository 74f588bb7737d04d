// MotionPredictor (issue 14), safety: stops, jumps, gaps, too fast, the horizon cut, the
// odometry twist, clear() and bad times. Expected poses from the closed forms of
// motion_test_oracle.h, never from the code under test.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "motion_test_oracle.h"
#include "rviz_projector/core/motion_predictor.h"

using namespace motion_oracle;  // NOLINT: the oracle's names read better bare here
using rviz_projector::MotionLimits;
using rviz_projector::PlanarTwist;

TEST(MotionPredictor, StoppingStopsThePredictionWithoutOvershoot)
{
  // 1 m/s straight, then standing from t = 0.5 s on; then driving again from 1.5 s.
  for (double rate : {10.0, 50.0, 200.0})
  {
    SCOPED_TRACE(testing::Message() << rate << " Hz");
    auto along = [](double t) { return t < 0.5 ? t : t < 1.5 ? 0.5 : 0.5 + (t - 1.5); };
    MotionPredictor mp;
    for (int k = 0; k <= static_cast<int>(2.0 * rate); ++k)
    {
      const double t = k / rate;
      const RigidTransform x = projectorOn({along(t), 0.0, 0.0});
      ASSERT_EQ(mp.add(stamp(k, rate), x), Added::Appended) << t;
      if (t < 0.3)
      {
        continue;
      }
      const Prediction p = ahead(mp, stamp(k, rate));
      if (t >= 0.5 + kHorizon - 1e-9 && t <= 1.5 + 1e-9)
      {
        // Standing for longer than the horizon: the newest pose exactly, no motion.
        SCOPED_TRACE(testing::Message() << "standing since " << t - 0.5 << " s");
        expectNewest(p, x, Prediction::Stopped);
        EXPECT_EQ(p.twist.vx, 0.0);
        EXPECT_EQ(p.twist.vy, 0.0);
        EXPECT_EQ(p.twist.wz, 0.0);
        EXPECT_EQ(p.speed, 0.0);
      }
      else if (t > 0.5 && t < 1.5)
      {
        // Just stopped: whatever it does, it never predicts beyond where 1 m/s would take it.
        EXPECT_LE(p.pose.translation().x, projectorOn({0.5 + kHorizon, 0.0, 0.0}).translation().x + 1e-9);
      }
      else if (t + kHorizon < 0.5 - 1e-9 || t >= 1.5 + 0.3)
      {
        // Driving (and not stopping before the target; or again, for 0.3 s): exact.
        EXPECT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state) << " at " << t;
        expectPose(p.pose, projectorOn({along(t + kHorizon), 0.0, 0.0}), kExact);
      }
    }
  }
}

TEST(MotionPredictor, JumpShowsTheNewestPoseThenPredictsAgain)
{
  // Relocalisation: the whole trajectory moves 1 m sideways (or turns by 1 rad about the origin)
  // at t = 0.5 s, at 50 Hz, driving on along the same twist.
  const double rate = 50.0;
  const std::pair<const char*, Motion> jumps[] = {{"1 m", {kArc.x0 + 0.6, kArc.y0 + 0.8, kArc.yaw0, kArc.v, kArc.w}},
                                                  {"1 rad", {kArc.x0, kArc.y0, kArc.yaw0 + 1.0, kArc.v, kArc.w}}};
  for (const auto& named : jumps)
  {
    SCOPED_TRACE(named.first);
    const Motion& after = named.second;
    MotionPredictor mp;
    feed(mp, kArc, rate, 0, 25);
    ASSERT_EQ(ahead(mp, stamp(25, rate)).state, Prediction::Predicted);
    const RigidTransform jumped = projectorOn(baseAt(after, 26 / rate));
    EXPECT_EQ(mp.add(stamp(26, rate), jumped), Added::Jump);
    expectNewest(ahead(mp, stamp(26, rate)), jumped, Prediction::Jump);
    // A sample from before the jump, arriving late, is not taken.
    EXPECT_EQ(mp.add(stamp(25, rate) + 0.01, projectorOn(baseAt(kArc, 25 / rate + 0.01))), Added::TooOld);
    // Until new samples span a fit, the newest pose; every extrapolation uses only samples after
    // the jump (a mix with the ones before would be off by a metre); predicting again by 0.25 s.
    for (int k = 27; k <= 45; ++k)
    {
      const RigidTransform x = projectorOn(baseAt(after, k / rate));
      ASSERT_EQ(mp.add(stamp(k, rate), x), Added::Appended) << k;
      const Prediction p = ahead(mp, stamp(k, rate));
      if (p.extrapolated())
      {
        EXPECT_EQ(p.state, Prediction::Predicted);
        expectPose(p.pose, projectorOn(baseAt(after, k / rate + kHorizon)), kExact);
      }
      else
      {
        EXPECT_TRUE(p.state == Prediction::Jump || p.state == Prediction::Collecting)
            << rviz_projector::predictionStateName(p.state);
        expectPose(p.pose, x, 1e-12);
        EXPECT_LT(k, 39) << "still no prediction 0.25 s after the jump";
      }
    }
  }
}

TEST(MotionPredictor, GapsStopThePrediction)
{
  const double rate = 50.0;
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 25);
  const double newest = stamp(25, rate);
  const RigidTransform last = projectorOn(baseAt(kArc, 25 / rate));
  // 0.1 s without a sample is no gap (the target may be anywhere up to the max horizon).
  const Prediction fine = mp.predict(newest + 0.1, newest + 0.12, kMaxHorizon);
  ASSERT_EQ(fine.state, Prediction::Predicted);
  expectPose(fine.pose, projectorOn(baseAt(kArc, 25 / rate + 0.12)), kExact);
  // At now = newest + 0.3 s (> max_gap 0.25), even for a short target: the newest pose.
  const Prediction gap = mp.predict(newest + 0.3, newest + 0.04, kMaxHorizon);
  expectNewest(gap, last, Prediction::Gap);
  // The next sample after the gap starts a new history: collecting, then exact again.
  const double t1 = 25 / rate + 0.3;
  const RigidTransform first = projectorOn(baseAt(kArc, t1));
  EXPECT_EQ(mp.add(kT0 + t1, first), Added::AfterGap);
  expectNewest(ahead(mp, kT0 + t1), first, Prediction::Collecting);
  for (int i = 1; i <= 12; ++i)
  {
    const double t = t1 + i / rate;
    ASSERT_EQ(mp.add(kT0 + t, projectorOn(baseAt(kArc, t))), Added::Appended);
  }
  const double t = t1 + 12 / rate;
  const Prediction p = ahead(mp, kT0 + t);
  ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state);
  expectPose(p.pose, projectorOn(baseAt(kArc, t + kHorizon)), kExact);
  // 10 Hz tf is no gap.
  MotionPredictor slow;
  feed(slow, kArc, 10.0, 0, 6);
}

TEST(MotionPredictor, TooFastIsNotExtrapolated)
{
  const double rate = 50.0;
  const std::pair<const char*, Motion> fast[] = {{"4 m/s", {0.0, 0.0, 0.0, 4.0, 0.0}},
                                                 {"4 rad/s", {0.0, 0.0, 0.0, 0.0, 4.0}}};
  for (const auto& named : fast)
  {
    SCOPED_TRACE(named.first);
    MotionPredictor mp;
    feed(mp, named.second, rate, 0, 20);  // no jump: slower than 5 m/s and 8 rad/s
    expectNewest(ahead(mp, stamp(20, rate)), projectorOn(baseAt(named.second, 20 / rate)), Prediction::TooFast);
  }
  // 2.5 m/s and 2.5 rad/s (a projector 0.32 m off the centre: 0.8 m/s) are fine.
  const Motion ok[] = {{0.0, 0.0, 0.0, 2.5, 0.0}, {0.0, 0.0, 0.0, 0.0, 2.5}};
  for (const Motion& m : ok)
  {
    MotionPredictor mp;
    feed(mp, m, rate, 0, 20);
    const Prediction p = ahead(mp, stamp(20, rate));
    ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state);
    expectPose(p.pose, projectorOn(baseAt(m, 20 / rate + kHorizon)), kExact);
  }
}

TEST(MotionPredictor, HorizonIsCutAtTheCallersMax)
{
  const double rate = 50.0;
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 25);
  const double newest = stamp(25, rate);
  const Prediction p = mp.predict(newest + 0.003, newest + 0.2, kMaxHorizon);
  EXPECT_EQ(p.state, Prediction::Limited);
  EXPECT_TRUE(p.extrapolated());
  EXPECT_NEAR(p.horizon, kMaxHorizon, 1e-9);
  EXPECT_NEAR(p.wanted, 0.2, 1e-9);
  expectPose(p.pose, projectorOn(baseAt(kArc, 25 / rate + kMaxHorizon)), kExact);
  // A max of 0: nothing extrapolated, the newest pose.
  const Prediction zero = mp.predict(newest + 0.003, newest + 0.05, 0.0);
  EXPECT_EQ(zero.state, Prediction::Limited);
  EXPECT_EQ(zero.horizon, 0.0);
  expectPose(zero.pose, projectorOn(baseAt(kArc, 25 / rate)), 1e-9);
}

TEST(MotionPredictor, OdometryTwistMovesTheMountAlongTheBaseArc)
{
  // The projector 0.3 m ahead of the base, 1.2 m up, tilted 30 deg down; tf samples of the arc.
  const double rate = 50.0;
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 25);
  const double newest = stamp(25, rate), t = 25 / rate;
  const RigidTransform base = baseTransform(baseAt(kArc, t));
  // The same twist as the tf samples: the closed-form pose.
  const Prediction p = mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, base, {kArc.v, 0.0, kArc.w});
  ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state);
  EXPECT_NEAR(p.horizon, kHorizon, 1e-9);
  EXPECT_NEAR(p.twist.wz, kArc.w, kExact);
  expectPose(p.pose, projectorOn(baseAt(kArc, t + kHorizon)), kExact);
  // Another twist than tf's (odometry is what counts): the mount on that twist's arc, from the
  // base's pose at the newest sample.
  const PlanarPose b = baseAt(kArc, t);
  for (const PlanarTwist& tw : {PlanarTwist{0.5, 0.0, -0.3}, PlanarTwist{0.8, 0.0, 0.0}, PlanarTwist{0.0, 0.0, 1.0}})
  {
    SCOPED_TRACE(testing::Message() << tw.vx << " m/s, " << tw.wz << " rad/s");
    const Motion m{b.x, b.y, b.yaw, tw.vx, tw.wz};
    const Prediction q = mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, base, tw);
    ASSERT_EQ(q.state, Prediction::Predicted) << rviz_projector::predictionStateName(q.state);
    EXPECT_NEAR(q.twist.wz, tw.wz, kExact);
    expectPose(q.pose, projectorOn(baseAt(m, kHorizon)), kExact);
  }
  // A sideways base twist (holonomic base).
  const PlanarTwist side{0.0, 0.4, 0.0};
  const Prediction s = mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, base, side);
  ASSERT_EQ(s.state, Prediction::Predicted);
  const PlanarPose moved{b.x - std::sin(b.yaw) * 0.4 * kHorizon, b.y + std::cos(b.yaw) * 0.4 * kHorizon, b.yaw};
  expectPose(s.pose, projectorOn(moved), kExact);
  // Cut at the max horizon too.
  const Prediction l = mp.predictWithTwist(newest + 0.003, newest + 0.2, kMaxHorizon, base, {kArc.v, 0.0, kArc.w});
  EXPECT_EQ(l.state, Prediction::Limited);
  expectPose(l.pose, projectorOn(baseAt(kArc, t + kMaxHorizon)), kExact);
}

TEST(MotionPredictor, OdometryTwistIsCheckedToo)
{
  const double rate = 50.0, nan = std::nan("");
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 25);
  const double newest = stamp(25, rate);
  const RigidTransform last = projectorOn(baseAt(kArc, 25 / rate));
  const RigidTransform base = baseTransform(baseAt(kArc, 25 / rate));
  expectNewest(mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, base, {4.0, 0.0, 0.0}), last,
               Prediction::TooFast);
  expectNewest(mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, base, {0.0, 0.0, 4.0}), last,
               Prediction::TooFast);
  expectNewest(mp.predictWithTwist(newest + 0.3, newest + kHorizon, kMaxHorizon, base, {kArc.v, 0.0, kArc.w}), last,
               Prediction::Gap);
  // A broken twist or base pose: no extrapolation, the newest pose.
  for (const PlanarTwist& tw : {PlanarTwist{nan, 0.0, 0.0}, PlanarTwist{0.5, 0.0, nan}})
  {
    const Prediction p = mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, base, tw);
    EXPECT_FALSE(p.extrapolated());
    expectPose(p.pose, last, 1e-12);
  }
  const RigidTransform bad = RigidTransform::fromQuaternion(0, 0, 0, 1, {nan, 0.0, 0.0});
  const Prediction p = mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, bad, {kArc.v, 0.0, kArc.w});
  EXPECT_FALSE(p.extrapolated());
  expectPose(p.pose, last, 1e-12);
  // Standing still by odometry: the newest pose.
  const Prediction still = mp.predictWithTwist(newest + 0.003, newest + kHorizon, kMaxHorizon, base, {});
  expectPose(still.pose, last, 1e-9);
}

TEST(MotionPredictor, ClearForgetsEverything)
{
  const double rate = 50.0;
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 25);
  EXPECT_EQ(mp.add(stamp(26, rate), projectorOn(baseAt(kStraight, 0.0))), Added::Jump);
  mp.clear();
  EXPECT_EQ(mp.size(), 0u);
  EXPECT_EQ(ahead(mp, stamp(26, rate)).state, Prediction::NoPose);
  // Time may start again (a bag restarted, sim time reset): older stamps are welcome after clear().
  feed(mp, kStraight, rate, -100, -80);
  const Prediction p = ahead(mp, stamp(-80, rate));
  ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state);
  expectPose(p.pose, projectorOn(baseAt(kStraight, -80 / rate + kHorizon)), kExact);
}

TEST(MotionPredictor, BadTimesDoNotCrash)
{
  const double rate = 50.0, nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 25);
  const double newest = stamp(25, rate);
  const RigidTransform last = projectorOn(baseAt(kArc, 25 / rate));
  for (const double target : {nan, -inf})
  {
    const Prediction p = mp.predict(newest + 0.003, target, kMaxHorizon);
    EXPECT_FALSE(p.extrapolated()) << target;
    expectPose(p.pose, last, 1e-12);
  }
  // An endless target is at most the max horizon away.
  const Prediction far = mp.predict(newest + 0.003, inf, kMaxHorizon);
  EXPECT_TRUE(rviz_projector::isFinite(far.pose.translation()));
  EXPECT_LE(far.horizon, kMaxHorizon + 1e-9);
  for (const double now : {nan, inf})
  {
    const Prediction p = mp.predict(now, newest + kHorizon, kMaxHorizon);
    EXPECT_TRUE(rviz_projector::isFinite(p.pose.translation())) << now;
  }
  const Prediction p = mp.predict(newest + 0.003, newest + kHorizon, nan);
  EXPECT_TRUE(rviz_projector::isFinite(p.pose.translation()));
  EXPECT_LE(p.horizon, kHorizon + 1e-9);
}

TEST(MotionPredictor, TheCallersLimitsCount)
{
  MotionLimits limits;
  limits.max_speed = 1.0;
  limits.jump_speed = 2.0;
  limits.window = 0.5;
  MotionPredictor mp(limits);
  EXPECT_EQ(mp.limits().max_speed, 1.0);
  const double rate = 50.0;
  // 1.5 m/s straight: too fast for these limits.
  const Motion m{0.0, 0.0, 0.0, 1.5, 0.0};
  feed(mp, m, rate, 0, 30);
  expectNewest(ahead(mp, stamp(30, rate)), projectorOn(baseAt(m, 30 / rate)), Prediction::TooFast);
  // A 3 m/s step is a jump for them (not for the defaults).
  EXPECT_EQ(mp.add(stamp(31, rate), projectorOn(baseAt(m, 31 / rate + 0.03))), Added::Jump);
  // A long window still predicts a constant twist exactly.
  mp.clear();
  feed(mp, kArc, rate, 0, 40);
  const Prediction p = ahead(mp, stamp(40, rate));
  ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state);
  expectPose(p.pose, projectorOn(baseAt(kArc, 40 / rate + kHorizon)), kExact);
}
