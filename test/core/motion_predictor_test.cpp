// MotionPredictor (issue 14): the projector's pose predicted from recent tf samples. The robot's
// base follows closed-form trajectories (unicycle arcs); the projector is mounted off the base's
// centre, turned and tilted; the expected poses are the mount on the base's closed-form pose at the
// target time, built here from quaternions by hand (never from the code under test).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "rviz_projector/core/motion_predictor.h"

using rviz_projector::MotionLimits;
using rviz_projector::MotionPredictor;
using rviz_projector::PlanarPose;
using rviz_projector::PlanarTwist;
using rviz_projector::Prediction;
using rviz_projector::RigidTransform;
using rviz_projector::Vec3;
using Added = MotionPredictor::Added;

namespace
{
const double kPi = std::acos(-1.0);
const double kDeg = kPi / 180.0;
const double kT0 = 1000.0;      // stamps are ROS times, far from 0
const double kHorizon = 0.05;   // s, the look-ahead of most tests
const double kMaxHorizon = 0.15;
const double kExact = 1e-6;     // m and rad: "predicted exactly"

struct Quat
{
  double x, y, z, w;
};
Quat operator*(const Quat& a, const Quat& b)
{
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
Quat aboutY(double a) { return {0, std::sin(a / 2), 0, std::cos(a / 2)}; }  // positive: nose down
Quat aboutZ(double a) { return {0, 0, std::sin(a / 2), std::cos(a / 2)}; }
const Quat kOptical{-0.5, 0.5, -0.5, 0.5};  // optical frame (z forward, x right, y down) of a body looking along x
RigidTransform pose(const Quat& q, const Vec3& t) { return RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, t); }

/// Where the projector's optical frame sits on the base: ahead, left, up (m), turned, tilted down.
struct Mount
{
  double x, y, z, yaw, tilt;
};
const Mount kMount{0.3, 0.1, 1.2, 0.2, 30 * kDeg};
const Mount kCentre{0.0, 0.0, 1.2, 0.0, 30 * kDeg};  // right above the base's turning centre

/// The base starts at (x0, y0, yaw0) at kT0 and drives at a constant body twist (v forward, w yaw).
struct Motion
{
  double x0, y0, yaw0, v, w;
};
const Motion kTurn{1.0, 2.0, 2.9, 0.0, 0.5};     // turns in place through +pi
const Motion kStraight{1.0, 2.0, 0.4, 1.0, 0.0};
const Motion kArc{-1.0, 0.5, -3.0, 0.7, 0.6};

/// Closed form of the base's pose t seconds after kT0.
PlanarPose baseAt(const Motion& m, double t)
{
  const double a = m.yaw0 + m.w * t;
  if (m.w == 0.0)
  {
    return {m.x0 + m.v * t * std::cos(a), m.y0 + m.v * t * std::sin(a), a};
  }
  return {m.x0 + m.v / m.w * (std::sin(a) - std::sin(m.yaw0)), m.y0 - m.v / m.w * (std::cos(a) - std::cos(m.yaw0)), a};
}

RigidTransform projectorOn(const PlanarPose& b, const Mount& mt = kMount)
{
  const double c = std::cos(b.yaw), s = std::sin(b.yaw);
  return pose(aboutZ(b.yaw + mt.yaw) * aboutY(mt.tilt) * kOptical,
              {b.x + c * mt.x - s * mt.y, b.y + s * mt.x + c * mt.y, mt.z});
}

RigidTransform baseTransform(const PlanarPose& b) { return pose(aboutZ(b.yaw), {b.x, b.y, 0.05}); }

/// The projector's own speed on the floor: |v + w x mount|.
double projectorSpeed(const Motion& m, const Mount& mt = kMount) { return std::hypot(m.v - m.w * mt.y, m.w * mt.x); }

double stamp(int k, double rate) { return kT0 + k / rate; }

/// Feeds samples k = first..last (inclusive) at `rate`; expects each to be appended.
void feed(MotionPredictor& mp, const Motion& m, double rate, int first, int last, const Mount& mt = kMount)
{
  for (int k = first; k <= last; ++k)
  {
    ASSERT_EQ(mp.add(stamp(k, rate), projectorOn(baseAt(m, k / rate), mt)), Added::Appended) << "sample " << k;
  }
}

/// Predicts kHorizon beyond the newest stamp `newest` (the present a little after it).
Prediction ahead(const MotionPredictor& mp, double newest, double horizon = kHorizon)
{
  return mp.predict(newest + 0.003, newest + horizon, kMaxHorizon);
}

double rotationError(const RigidTransform& a, const RigidTransform& b)
{
  double e = 0.0;
  for (int i = 0; i < 9; ++i)
  {
    e = std::max(e, std::fabs(a.rotation()[i] - b.rotation()[i]));
  }
  return e;
}
double distance(const RigidTransform& a, const RigidTransform& b) { return rviz_projector::norm(a.translation() - b.translation()); }

void expectPose(const RigidTransform& actual, const RigidTransform& expected, double tol)
{
  EXPECT_LT(distance(actual, expected), tol) << "at (" << actual.translation().x << ", " << actual.translation().y << ", "
                                             << actual.translation().z << "), expected (" << expected.translation().x
                                             << ", " << expected.translation().y << ", " << expected.translation().z << ")";
  EXPECT_LT(rotationError(actual, expected), tol);
}

/// Not extrapolated: the newest pose as it is.
void expectNewest(const Prediction& p, const RigidTransform& newest, Prediction::State state)
{
  EXPECT_EQ(p.state, state) << rviz_projector::predictionStateName(p.state);
  EXPECT_FALSE(p.extrapolated());
  EXPECT_EQ(p.horizon, 0.0);
  expectPose(p.pose, newest, 1e-12);
}

/// Heading of the optical axis (z) on the floor.
double lookHeading(const RigidTransform& p) { return std::atan2(p.rotation()[5], p.rotation()[2]); }
}  // namespace

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
  const double rate = 50.0;
  MotionPredictor in_order, shuffled;
  feed(in_order, kArc, rate, 0, 30);
  // Every other pair arrives swapped; one sample comes three periods late.
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
  int newest = -1;
  for (int k : order)
  {
    const Added a = shuffled.add(stamp(k, rate), projectorOn(baseAt(kArc, k / rate)));
    EXPECT_EQ(a, k > newest ? Added::Appended : Added::Inserted) << "sample " << k;
    newest = std::max(newest, k);
  }
  EXPECT_EQ(shuffled.size(), in_order.size());
  const Prediction a = ahead(in_order, stamp(30, rate));
  const Prediction b = ahead(shuffled, stamp(30, rate));
  ASSERT_EQ(b.state, Prediction::Predicted);
  expectPose(b.pose, a.pose, 1e-9);
  expectPose(b.pose, projectorOn(baseAt(kArc, 30 / rate + kHorizon)), kExact);
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
  EXPECT_EQ(mp.add(nan, ok), Added::NotFinite);
  EXPECT_EQ(mp.add(inf, ok), Added::NotFinite);
  EXPECT_EQ(mp.add(-inf, ok), Added::NotFinite);
  EXPECT_EQ(mp.add(stamp(21, rate), RigidTransform::fromQuaternion(0, 0, 0, 1, {nan, 0.0, 1.0})), Added::NotFinite);
  EXPECT_EQ(mp.add(stamp(21, rate), RigidTransform::fromQuaternion(0, 0, 0, 1, {0.0, inf, 1.0})), Added::NotFinite);
  EXPECT_EQ(mp.add(stamp(21, rate), RigidTransform::fromQuaternion(0, 0, 0, 1, {0.0, 0.0, -inf})), Added::NotFinite);
  EXPECT_EQ(mp.size(), 21u);
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
  const std::pair<const char*, Motion> fast[] = {{"4 m/s", {0.0, 0.0, 0.0, 4.0, 0.0}}, {"4 rad/s", {0.0, 0.0, 0.0, 0.0, 4.0}}};
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
