// MotionPredictor (issue 14), fitting: a constant twist predicted exactly, noise, out-of-order,
// duplicated and bad samples, acceleration. The robot's base follows closed-form trajectories; the
// projector is mounted off its centre, turned and tilted; the expected poses are the mount on the
// base's closed-form pose at the target time (motion_test_oracle.h), never the code under test's.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "motion_test_oracle.h"
#include "rviz_projector/core/motion_predictor.h"

using namespace motion_oracle;  // NOLINT: the oracle's names read better bare here

TEST(MotionPredictor, NoPoseWithoutSamples)
{
  const MotionPredictor mp;
  EXPECT_EQ(mp.size(), 0u);
  const Prediction p = mp.predict(kT0, kT0 + kHorizon, kMaxHorizon);
  EXPECT_EQ(p.state, Prediction::NoPose);
  EXPECT_FALSE(p.extrapolated());
  const Prediction q = mp.predictWithTwist(kT0, kT0 + kHorizon, kMaxHorizon, RigidTransform(), {1.0, 0.0, 0.0});
  EXPECT_EQ(q.state, Prediction::NoPose);
  EXPECT_FALSE(q.extrapolated());
}

TEST(MotionPredictor, OneSampleIsCollecting)
{
  MotionPredictor mp;
  const RigidTransform first = projectorOn(baseAt(kArc, 0.0));
  EXPECT_EQ(mp.add(kT0, first), Added::Appended);
  const Prediction p = ahead(mp, kT0);
  expectNewest(p, first, Prediction::Collecting);
  EXPECT_DOUBLE_EQ(p.newest, kT0);
}

TEST(MotionPredictor, ConstantTwistIsPredictedExactly)
{
  const std::pair<const char*, Motion> motions[] = {{"turn in place", kTurn}, {"straight", kStraight}, {"arc", kArc}};
  for (const auto& named : motions)
  {
    const Motion& m = named.second;
    for (double rate : {10.0, 50.0, 200.0})
    {
      SCOPED_TRACE(testing::Message() << named.first << " at " << rate << " Hz");
      MotionPredictor mp;
      const int warm = static_cast<int>(std::ceil(0.3 * rate));  // 0.3 s of samples first
      feed(mp, m, rate, 0, warm);
      // Then a prediction after every sample for 0.5 s more (the turn crosses +-pi meanwhile).
      for (int k = warm + 1; k <= warm + static_cast<int>(0.5 * rate); ++k)
      {
        feed(mp, m, rate, k, k);
        const double t = k / rate;
        const Prediction p = ahead(mp, stamp(k, rate));
        ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state) << " at " << t;
        EXPECT_TRUE(p.extrapolated());
        EXPECT_NEAR(p.horizon, kHorizon, 1e-9);
        EXPECT_NEAR(p.wanted, kHorizon, 1e-9);
        EXPECT_DOUBLE_EQ(p.newest, stamp(k, rate));
        EXPECT_NEAR(p.twist.wz, m.w, kExact);
        EXPECT_NEAR(p.speed, projectorSpeed(m), kExact);
        expectPose(p.pose, projectorOn(baseAt(m, t + kHorizon)), kExact);
      }
    }
  }
}

TEST(MotionPredictor, ProjectorAboveTheTurningCentreTurnsWithoutMoving)
{
  // Its position stands still while its heading turns at 0.5 rad/s: not a stop.
  for (double rate : {10.0, 50.0, 200.0})
  {
    SCOPED_TRACE(testing::Message() << rate << " Hz");
    MotionPredictor mp;
    const int last = static_cast<int>(0.4 * rate);
    feed(mp, kTurn, rate, 0, last, kCentre);
    const Prediction p = ahead(mp, stamp(last, rate));
    ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state);
    EXPECT_NEAR(p.twist.wz, 0.5, kExact);
    EXPECT_NEAR(p.speed, 0.0, kExact);
    expectPose(p.pose, projectorOn(baseAt(kTurn, last / rate + kHorizon), kCentre), kExact);
  }
}

TEST(MotionPredictor, NoisySamplesGiveABoundedError)
{
  // tf jitter: 1 mm (each axis) and 0.1 deg (heading and tilt) of Gaussian noise, arc at 50 Hz.
  // Bound, derived for the crudest sound fit (the chord across a 0.1 s window, extrapolated from
  // the noisy newest pose): per axis the error is e_n (1 + h/T) - e_0 h/T, std
  // sigma sqrt(1.5^2 + 0.5^2) = 1.58 sigma; on the floor (2 axes) an RMS of 2.2 mm and a heading
  // RMS of 2.8e-3 rad. Allowed: RMS 3 mm and 5e-3 rad, worst 8 mm and 0.014 rad (5 sigma). Without
  // prediction the error would be the 33 mm the projector travels in 50 ms.
  const double sigma_p = 0.001, sigma_a = 0.1 * kDeg, rate = 50.0;
  std::mt19937 rng(14);
  std::normal_distribution<double> noise(0.0, 1.0);
  MotionPredictor mp;
  double sum_p = 0.0, sum_a = 0.0, worst_p = 0.0, worst_a = 0.0;
  int n = 0;
  for (int k = 0; k <= static_cast<int>(3.0 * rate); ++k)
  {
    const double t = k / rate;
    // Heading and tilt noise on the projector itself; position noise on its origin (put on the
    // base's position and the mount's height: the same shift).
    Mount mt = kMount;
    mt.yaw += sigma_a * noise(rng);
    mt.tilt += sigma_a * noise(rng);
    mt.z += sigma_p * noise(rng);
    PlanarPose b = baseAt(kArc, t);
    b.x += sigma_p * noise(rng);
    b.y += sigma_p * noise(rng);
    ASSERT_EQ(mp.add(stamp(k, rate), projectorOn(b, mt)), Added::Appended) << k;
    if (t < 0.3)
    {
      continue;
    }
    const Prediction p = ahead(mp, stamp(k, rate));
    ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state) << " at " << t;
    const RigidTransform expected = projectorOn(baseAt(kArc, t + kHorizon));
    const Vec3 e = p.pose.translation() - expected.translation();
    const double ep = std::hypot(e.x, e.y);
    const double ea = std::fabs(std::remainder(lookHeading(p.pose) - lookHeading(expected), 2 * kPi));
    sum_p += ep * ep;
    sum_a += ea * ea;
    worst_p = std::max(worst_p, ep);
    worst_a = std::max(worst_a, ea);
    ++n;
  }
  ASSERT_GT(n, 100);
  EXPECT_LT(std::sqrt(sum_p / n), 0.003);
  EXPECT_LT(worst_p, 0.008);
  EXPECT_LT(std::sqrt(sum_a / n), 0.005);
  EXPECT_LT(worst_a, 0.014);
}

TEST(MotionPredictor, OutOfOrderStampsGiveTheSamePrediction)
{
  // Every other pair arrives swapped and one sample comes three periods late. Two motions: the
  // constant arc (predicted exactly), and a speeding up, tightening turn (whatever the fit makes of
  // it, the same as from the samples in order: the window holds the same samples).
  const double rate = 50.0;
  std::vector<int> order;
  for (int k = 0; k <= 30; ++k)
  {
    order.push_back(k);
  }
  for (std::size_t i = 1; i + 1 < order.size(); i += 4)
  {
    std::swap(order[i], order[i + 1]);
  }
  order.erase(std::find(order.begin(), order.end(), 25));
  order.insert(std::find(order.begin(), order.end(), 28) + 1, 25);
  auto arc = [](double t) { return projectorOn(baseAt(kArc, t)); };
  auto varying = [](double t) { return projectorOn({0.5 * t + 0.5 * t * t, 0.1 * t * t, 0.3 * t * t}); };
  for (int motion = 0; motion < 2; ++motion)
  {
    SCOPED_TRACE(motion == 0 ? "arc" : "varying");
    auto at = [&](double t) { return motion == 0 ? arc(t) : varying(t); };
    MotionPredictor in_order, shuffled;
    int newest = -1, next = 0;
    for (int k : order)
    {
      ASSERT_EQ(in_order.add(stamp(next, rate), at(next / rate)), Added::Appended);
      ++next;
      const Added a = shuffled.add(stamp(k, rate), at(k / rate));
      EXPECT_EQ(a, k > newest ? Added::Appended : Added::Inserted) << "sample " << k;
      newest = std::max(newest, k);
      EXPECT_DOUBLE_EQ(ahead(shuffled, stamp(newest, rate)).newest, stamp(newest, rate)) << "sample " << k;
    }
    EXPECT_EQ(shuffled.size(), in_order.size());
    const Prediction a = ahead(in_order, stamp(30, rate));
    const Prediction b = ahead(shuffled, stamp(30, rate));
    ASSERT_EQ(b.state, Prediction::Predicted) << rviz_projector::predictionStateName(b.state);
    EXPECT_EQ(a.state, b.state);
    EXPECT_NEAR(b.horizon, kHorizon, 1e-9);
    EXPECT_NEAR(b.twist.vx, a.twist.vx, 1e-9);
    EXPECT_NEAR(b.twist.vy, a.twist.vy, 1e-9);
    EXPECT_NEAR(b.twist.wz, a.twist.wz, 1e-9);
    expectPose(b.pose, a.pose, 1e-9);
    if (motion == 0)
    {
      expectPose(b.pose, projectorOn(baseAt(kArc, 30 / rate + kHorizon)), kExact);
    }
  }
}

TEST(MotionPredictor, DuplicatedStampsAreIgnored)
{
  const double rate = 50.0;
  MotionPredictor clean, dup;
  feed(clean, kStraight, rate, 0, 20);
  feed(dup, kStraight, rate, 0, 20);
  const std::size_t n = dup.size();
  // The same sample again, the same stamp with another pose, a stamp 0.5 us off, an older one.
  EXPECT_EQ(dup.add(stamp(20, rate), projectorOn(baseAt(kStraight, 20 / rate))), Added::Duplicate);
  EXPECT_EQ(dup.add(stamp(20, rate), projectorOn(baseAt(kStraight, 20 / rate + 0.01))), Added::Duplicate);
  EXPECT_EQ(dup.add(stamp(20, rate) + 0.5e-6, projectorOn(baseAt(kStraight, 20 / rate + 0.002))), Added::Duplicate);
  EXPECT_EQ(dup.add(stamp(18, rate) - 0.5e-6, projectorOn(baseAt(kStraight, 0.0))), Added::Duplicate);
  EXPECT_EQ(dup.size(), n);
  const Prediction p = ahead(dup, stamp(20, rate));
  ASSERT_EQ(p.state, Prediction::Predicted);
  expectPose(p.pose, ahead(clean, stamp(20, rate)).pose, 1e-12);
  expectPose(p.pose, projectorOn(baseAt(kStraight, 20 / rate + kHorizon)), kExact);
}

TEST(MotionPredictor, ZeroIntervalLookupsOfASlowTfCountOnce)
{
  // A display at 60 Hz looking up a 10 Hz tf gets each stamp six times: no zero-interval steps
  // (no infinite speeds, no false stop) and the prediction stays exact.
  const double rate = 10.0;
  MotionPredictor mp;
  for (int k = 0; k <= 8; ++k)
  {
    const RigidTransform x = projectorOn(baseAt(kArc, k / rate));
    EXPECT_EQ(mp.add(stamp(k, rate), x), Added::Appended);
    for (int i = 0; i < 5; ++i)
    {
      EXPECT_EQ(mp.add(stamp(k, rate), x), Added::Duplicate);
    }
    if (k >= 3)
    {
      const Prediction p = ahead(mp, stamp(k, rate));
      ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state) << " at " << k;
      expectPose(p.pose, projectorOn(baseAt(kArc, k / rate + kHorizon)), kExact);
    }
  }
  EXPECT_LE(mp.size(), 9u);
}

TEST(MotionPredictor, TooOldSamplesAreIgnored)
{
  const double rate = 50.0;
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 100);
  const std::size_t n = mp.size();
  EXPECT_EQ(mp.add(kT0 - 1.0, projectorOn(baseAt(kArc, -1.0))), Added::TooOld);
  EXPECT_EQ(mp.size(), n);
  const Prediction p = ahead(mp, stamp(100, rate));
  ASSERT_EQ(p.state, Prediction::Predicted);
  expectPose(p.pose, projectorOn(baseAt(kArc, 100 / rate + kHorizon)), kExact);
}

TEST(MotionPredictor, NotFiniteSamplesAreRejected)
{
  const double rate = 50.0, nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  MotionPredictor mp;
  feed(mp, kArc, rate, 0, 20);
  const RigidTransform ok = projectorOn(baseAt(kArc, 21 / rate));
  // The history kept is the predictor's business (it keeps max_gap seconds): rejected samples
  // leave it as it was.
  const std::size_t kept = mp.size();
  EXPECT_EQ(mp.add(nan, ok), Added::NotFinite);
  EXPECT_EQ(mp.add(inf, ok), Added::NotFinite);
  EXPECT_EQ(mp.add(-inf, ok), Added::NotFinite);
  EXPECT_EQ(mp.add(stamp(21, rate), RigidTransform::fromQuaternion(0, 0, 0, 1, {nan, 0.0, 1.0})), Added::NotFinite);
  EXPECT_EQ(mp.add(stamp(21, rate), RigidTransform::fromQuaternion(0, 0, 0, 1, {0.0, inf, 1.0})), Added::NotFinite);
  EXPECT_EQ(mp.add(stamp(21, rate), RigidTransform::fromQuaternion(0, 0, 0, 1, {0.0, 0.0, -inf})), Added::NotFinite);
  EXPECT_EQ(mp.size(), kept);
  // Later samples and predictions as if nothing happened.
  feed(mp, kArc, rate, 21, 25);
  const Prediction p = ahead(mp, stamp(25, rate));
  ASSERT_EQ(p.state, Prediction::Predicted) << rviz_projector::predictionStateName(p.state);
  expectPose(p.pose, projectorOn(baseAt(kArc, 25 / rate + kHorizon)), kExact);
}

TEST(MotionPredictor, HistoryIsBounded)
{
  // 20 s of tf at 200 Hz: what is kept stays within 2 s (window 0.12 s, max gap 0.25 s).
  MotionPredictor mp;
  feed(mp, kArc, 200.0, 0, 4000);
  EXPECT_LE(mp.size(), 400u);
  EXPECT_GE(mp.size(), 3u);
}

TEST(MotionPredictor, AccelerationLagsButStaysBounded)
{
  // Straight, speed ramping 0.2 -> 2.0 m/s at 1 m/s^2 (and back down), tf at 50 Hz. A fit of past
  // samples sees the mean speed over its window (at most the window plus one period, W = 0.14 s,
  // before the newest): it lags by at most a (h^2/2 + W h) = 8.25 mm when speeding up, leads as
  // much when slowing down, and is never worse than no prediction (v h + a h^2 / 2).
  const double rate = 50.0, a = 1.0, v0 = 0.2, h = kHorizon, bound = a * (h * h / 2 + 0.14 * h);
  for (double sign : {1.0, -1.0})
  {
    SCOPED_TRACE(sign > 0 ? "speeding up" : "slowing down");
    const double start = sign > 0 ? v0 : 2.0;
    auto along = [&](double t) { return start * t + sign * a * t * t / 2; };  // metres driven
    MotionPredictor mp;
    for (int k = 0; k <= static_cast<int>(1.8 * rate); ++k)
    {
      const double t = k / rate;
      ASSERT_EQ(mp.add(stamp(k, rate), projectorOn({along(t), 0.0, 0.0})), Added::Appended);
      if (t < 0.2)
      {
        continue;
      }
      const Prediction p = ahead(mp, stamp(k, rate));
      ASSERT_EQ(p.state, Prediction::Predicted) << t;
      const RigidTransform truth = projectorOn({along(t + h), 0.0, 0.0});
      const double err = p.pose.translation().x - truth.translation().x;  // + ahead, - behind
      EXPECT_LE(std::fabs(err), bound + 1e-9) << t;
      EXPECT_LE(sign * err, 1e-9) << "lags (speeding up) or leads (slowing down) at " << t;
      EXPECT_LT(std::fabs(err), start * h + sign * a * t * h) << t;
      EXPECT_NEAR(p.pose.translation().y, truth.translation().y, kExact);
      EXPECT_LT(rotationError(p.pose, truth), kExact);
    }
  }
}
