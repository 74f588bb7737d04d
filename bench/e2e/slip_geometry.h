// The maths of the motion slip benchmark (scripts/bench --slip, bench/e2e/slip_probe.cpp): the
// synthetic robot's analytic trajectories, the world-locked stripe patterns on the floor, and the
// floor point a projector pixel's ray hits. Plain maths, no ROS, no X.
//
// Frames: map (fixed, z up), base_link (the robot: x forward, y left, z up, on the floor), the
// projector's optical frame (z along the beam, x right, y down; pixel centres at integer
// coordinates, as in OpenCV and a ROS CameraInfo).
#pragma once

#include <array>
#include <string>
#include <vector>

namespace slip
{
struct Vec2
{
  double x = 0.0;
  double y = 0.0;
};

/// The robot at one time: base_link's pose in map and its velocity (base origin, map frame).
struct RobotState
{
  double x = 0.0, y = 0.0, yaw = 0.0;
  double vx = 0.0, vy = 0.0, yaw_rate = 0.0;
};

enum class Motion
{
  Still,     // standing at (0, 0), yaw 0.05 rad: the geometry's floor (slip ~0)
  Turn,      // turning in place at 0.5 rad/s about (0, 0)
  Straight,  // driving along +x at 1 m/s from (0, 0)
  SCurve,    // 0.7 m/s, yaw rate 0.6 sin(2 pi t / 4 s) rad/s: a smooth S (heading -0.38 .. +0.38 rad),
             // at most 0.94 rad/s^2 of angular acceleration, as a robot can follow
  SCurveSteps  // stress: 0.7 m/s, yaw rate +0.6 / -0.6 rad/s switching instantly every 2 s (heading
               // -0.6 .. +0.6 rad): infinite angular acceleration, which no constant-twist prediction follows
};

/// "still", "turn", "straight", "scurve", "scurve-steps"; parseMotion returns false for anything else.
std::string motionName(Motion m);
bool parseMotion(const std::string& name, Motion& m);

/// The analytic trajectory: the robot's state t seconds after the motion started (t < 0: t = 0).
RobotState robotState(Motion m, double t);

/// A world-locked floor stripe: the centre line from a to b, `width` wide (metres, map frame).
struct Stripe
{
  Vec2 a, b;
};

/// Where a floor point is relative to the nearest true stripe centre line.
struct StripeDistance
{
  double distance = 0.0;  // signed, along `normal` (metres)
  Vec2 normal;            // unit normal of that stripe
  double pitch = 0.0;     // distance to the neighbouring stripes at this point (ambiguity limit)
};

/**
 * The stripes laid out for one motion, chosen so they cross the sampled image row (which lies
 * across the robot's heading, ~1.6 m ahead of the projector) at a good angle:
 *  - still: parallel lines 0.3 m apart at 45 deg to the row (an error in the image column or row
 *    of the sampled pixels, or in the mount, shows as about 1 mm per pixel).
 *  - turn: radial lines around (0, 0) every 12 deg, 0.8 .. 3.0 m from the centre: the floor under
 *    the row moves along the row, across these lines.
 *  - straight: parallel lines 0.4 m apart, their normal 20 deg from the direction of travel (+x):
 *    across-stripe slip = cos 20 deg = 0.94 of the slip along the travel.
 *  - scurve: lines along the mean travel (+x), 0.4 m apart: under the row the floor moves mostly
 *    sideways (yaw rate x 1.7 m = 1.0 m/s against 0.7 m/s forward); the heading swings +-0.6 rad,
 *    so they cross the row at 56 .. 90 deg, and the motion across them is 0.47 .. 1.25 m/s.
 */
class StripePattern
{
public:
  static StripePattern forMotion(Motion m);

  /// The stripes' centre lines, clipped to the area the projector sees during the motion.
  std::vector<Stripe> stripes() const;
  StripeDistance nearest(const Vec2& p) const;
  double width() const { return width_; }

private:
  bool radial_ = false;
  // radial: centre, angular pitch, radii; parallel: normal angle, pitch, clip box.
  Vec2 centre_;
  double angle_step_ = 0.0, r_min_ = 0.0, r_max_ = 0.0;
  double normal_angle_ = 0.0, pitch_ = 0.0;
  double x_min_ = 0.0, x_max_ = 0.0, y_min_ = 0.0, y_max_ = 0.0;
  double width_ = 0.010;
};

/// A pinhole lens without distortion (the CameraInfo's K) and its mount on base_link.
struct Projector
{
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;
  int width = 0, height = 0;
  std::array<double, 3> mount_t{};  // optical frame origin in base_link
  std::array<double, 9> mount_r{};  // optical -> base_link rotation (row major)
};

/**
 * The demo's projector (config/demo_projector.yaml, launch/demo.launch): 1280x800, fx = fy = 1300,
 * centred (639.5, 399.5); 0.15 m ahead of base_link, 1.2 m high, pitched down atan2(1.2, 1.0).
 */
Projector demoProjector();

/// The floor point (map, z = 0) that image pixel (u, v) lights with the robot in `state`; false
/// when the ray does not go down to the floor.
bool floorPoint(const Projector& p, const RobotState& state, double u, double v, Vec2& out);

/// Velocity (map) of the robot-fixed point that is at floor point p now.
Vec2 pointVelocity(const RobotState& state, const Vec2& p);

/**
 * Slip of a stripe drawn through floor point p (where a lit pixel lands): its signed distance
 * across the nearest true stripe, in metres, positive when it lies displaced along the motion of
 * the robot at that point (content drawn from an older pose: it lags behind the motion).
 * `ambiguous` is set when the distance is over 0.4 of the stripe pitch (cannot tell which stripe);
 * `speed` (if given) receives how fast the floor under p moves across that stripe (m/s, >= 0).
 */
double slipAt(const StripePattern& pattern, const RobotState& state, const Vec2& p, bool& ambiguous,
              double* speed = nullptr);
}  // namespace slip
