// Test oracle of the motion compensation tests (issue 14): a robot base on closed-form unicycle
// trajectories carrying a projector mounted off its centre, turned and tilted; poses built from
// quaternions by hand, never from the code under test.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "rviz_projector/core/motion_predictor.h"

namespace motion_oracle
{
using rviz_projector::MotionPredictor;
using rviz_projector::PlanarPose;
using rviz_projector::Prediction;
using rviz_projector::RigidTransform;
using rviz_projector::Vec3;
using Added = MotionPredictor::Added;

inline const double kPi = std::acos(-1.0);
inline const double kDeg = kPi / 180.0;
inline const double kT0 = 1000.0;  // stamps are ROS times, far from 0
inline const double kHorizon = 0.05;  // s, the look-ahead of most tests
inline const double kMaxHorizon = 0.15;
inline const double kExact = 1e-6;  // m and rad: "predicted exactly"

/// A quaternion (x, y, z, w); a * b is the rotation b, then a.
struct Quat
{
  double x, y, z, w;
};
inline Quat operator*(const Quat& a, const Quat& b)
{
  return {a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y, a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
          a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w, a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z};
}
inline Quat aboutX(double a) { return {std::sin(a / 2), 0, 0, std::cos(a / 2)}; }
inline Quat aboutY(double a) { return {0, std::sin(a / 2), 0, std::cos(a / 2)}; }  // positive: nose down
inline Quat aboutZ(double a) { return {0, 0, std::sin(a / 2), std::cos(a / 2)}; }
/// The optical frame (z forward, x right, y down) of a body looking along its x axis.
inline const Quat kOptical{-0.5, 0.5, -0.5, 0.5};
inline RigidTransform pose(const Quat& q, const Vec3& t)
{
  return RigidTransform::fromQuaternion(q.x, q.y, q.z, q.w, t);
}

/// Where the projector's optical frame sits on the base: ahead, left, up (m), turned, tilted down.
struct Mount
{
  double x, y, z, yaw, tilt;
};
inline const Mount kMount{0.3, 0.1, 1.2, 0.2, 30 * kDeg};
inline const Mount kCentre{0.0, 0.0, 1.2, 0.0, 30 * kDeg};  // right above the base's turning centre

/// The base starts at (x0, y0, yaw0) at kT0 and drives at a constant body twist (v forward, w yaw).
struct Motion
{
  double x0, y0, yaw0, v, w;
};
inline const Motion kTurn{1.0, 2.0, 2.9, 0.0, 0.5};     // turns in place through +pi
inline const Motion kStraight{1.0, 2.0, 0.4, 1.0, 0.0};
inline const Motion kArc{-1.0, 0.5, -3.0, 0.7, 0.6};

/// Closed form of the base's pose t seconds after kT0.
inline PlanarPose baseAt(const Motion& m, double t)
{
  const double a = m.yaw0 + m.w * t;
  if (m.w == 0.0)
  {
    return {m.x0 + m.v * t * std::cos(a), m.y0 + m.v * t * std::sin(a), a};
  }
  return {m.x0 + m.v / m.w * (std::sin(a) - std::sin(m.yaw0)), m.y0 - m.v / m.w * (std::cos(a) - std::cos(m.yaw0)), a};
}

inline RigidTransform projectorOn(const PlanarPose& b, const Mount& mt = kMount)
{
  const double c = std::cos(b.yaw), s = std::sin(b.yaw);
  return pose(aboutZ(b.yaw + mt.yaw) * aboutY(mt.tilt) * kOptical,
              {b.x + c * mt.x - s * mt.y, b.y + s * mt.x + c * mt.y, mt.z});
}

inline RigidTransform baseTransform(const PlanarPose& b) { return pose(aboutZ(b.yaw), {b.x, b.y, 0.05}); }

/// The projector's own speed on the floor: |v + w x mount|.
inline double projectorSpeed(const Motion& m, const Mount& mt = kMount)
{
  return std::hypot(m.v - m.w * mt.y, m.w * mt.x);
}

inline double stamp(int k, double rate) { return kT0 + k / rate; }

/// Feeds samples k = first..last (inclusive) at `rate`; expects each to be appended.
inline void feed(MotionPredictor& mp, const Motion& m, double rate, int first, int last, const Mount& mt = kMount)
{
  for (int k = first; k <= last; ++k)
  {
    ASSERT_EQ(mp.add(stamp(k, rate), projectorOn(baseAt(m, k / rate), mt)), Added::Appended) << "sample " << k;
  }
}

/// Predicts kHorizon beyond the newest stamp `newest` (the present a little after it).
inline Prediction ahead(const MotionPredictor& mp, double newest, double horizon = kHorizon)
{
  return mp.predict(newest + 0.003, newest + horizon, kMaxHorizon);
}

inline double rotationError(const RigidTransform& a, const RigidTransform& b)
{
  double e = 0.0;
  for (int i = 0; i < 9; ++i)
  {
    e = std::max(e, std::fabs(a.rotation()[i] - b.rotation()[i]));
  }
  return e;
}
inline double distance(const RigidTransform& a, const RigidTransform& b)
{
  return rviz_projector::norm(a.translation() - b.translation());
}

inline void expectPose(const RigidTransform& actual, const RigidTransform& expected, double tol)
{
  const Vec3& a = actual.translation();
  const Vec3& e = expected.translation();
  EXPECT_LT(distance(actual, expected), tol)
      << "at (" << a.x << ", " << a.y << ", " << a.z << "), expected (" << e.x << ", " << e.y << ", " << e.z << ")";
  EXPECT_LT(rotationError(actual, expected), tol);
}

/// Not extrapolated: the newest pose as it is.
inline void expectNewest(const Prediction& p, const RigidTransform& newest, Prediction::State state)
{
  EXPECT_EQ(p.state, state) << rviz_projector::predictionStateName(p.state);
  EXPECT_FALSE(p.extrapolated());
  EXPECT_EQ(p.horizon, 0.0);
  expectPose(p.pose, newest, 1e-12);
}

/// Heading of the optical axis (z) on the floor.
inline double lookHeading(const RigidTransform& p) { return std::atan2(p.rotation()[5], p.rotation()[2]); }
}  // namespace motion_oracle
