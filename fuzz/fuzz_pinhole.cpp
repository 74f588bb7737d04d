// libFuzzer target: PinholeModel::fromCalibration (a CameraInfo's numbers from the fuzz input:
// sizes 0/1/huge, P or K zero, NaN/Inf anywhere, negative/zero/tiny/huge focal lengths, unknown
// distortion models, binning and ROI), then project / ray / centre / glProjectionMatrix and a
// FloorFootprint from a pose with a possibly zero or NaN quaternion. Invariants: no crash or UB;
// a refused calibration leaves the model unchanged and says why; an accepted one is positive,
// finite and within kMaxResolution; for sane finite inputs every output is finite; for
// well-conditioned lenses (Tx/Ty included) pixel -> ray -> project gives the pixel back and point
// -> project -> ray (from the optical centre) gives the point back, within a tolerance relative to
// the magnitudes involved.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_input.h"
#include "rviz_projector/core/floor_footprint.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/rigid_transform.h"

using namespace rviz_projector;
using rviz_projector_fuzz::Input;
using rviz_projector_fuzz::sane;

namespace
{
std::uint32_t dimension(Input& in)
{
  static const std::uint32_t interesting[] = {0u, 1u, 2u, 640u, 800u, 1280u, 16384u, 16385u, 20000u, 0xffffffffu};
  return in.boolean() ? interesting[in.integer<std::size_t>(0, 9)] : in.integer<std::uint32_t>();
}

LensCalibration calibrationFrom(Input& in)
{
  LensCalibration c;
  c.width = dimension(in);
  c.height = dimension(in);
  const double f = in.number(3000.0), cx = in.number(2000.0), cy = in.number(2000.0);
  const int layout = in.integer<int>(0, 3);
  if (layout == 0 || layout == 2)
  {
    c.K = {f, 0, cx, 0, in.boolean() ? f : in.number(3000.0), cy, 0, 0, 1};
  }
  if (layout == 1 || layout == 2)
  {
    c.P = {f, 0, cx, in.boolean() ? 0.0 : in.number(100.0), 0, in.boolean() ? f : in.number(3000.0), cy,
           in.boolean() ? 0.0 : in.number(100.0), 0, 0, 1, 0};
  }
  if (layout == 3)
  {
    for (double& v : c.K) v = in.number(3000.0);
    for (double& v : c.P) v = in.number(3000.0);
  }
  // Now and then one entry anywhere spoiled.
  if (in.boolean())
  {
    const std::size_t i = in.integer<std::size_t>(0, 20);
    (i < 9 ? c.K[i] : c.P[i - 9]) = in.number(1e9);
  }
  static const char* models[] = {"", "plumb_bob", "rational_polynomial", "equidistant", "fisheye", "\xff\xfe"};
  c.distortion_model = in.boolean() ? std::string(models[in.integer<std::size_t>(0, 5)]) : in.text(16);
  c.D.resize(in.integer<std::size_t>(0, 14));
  for (double& d : c.D) d = in.boolean() ? 0.0 : in.number(1.0);
  c.binning_x = in.boolean() ? 0u : in.integer<std::uint32_t>();
  c.binning_y = in.boolean() ? 0u : in.integer<std::uint32_t>();
  if (in.boolean())
  {
    c.roi_x_offset = in.integer<std::uint32_t>();
    c.roi_y_offset = in.integer<std::uint32_t>();
    c.roi_width = in.integer<std::uint32_t>(0, 4096);
    c.roi_height = in.integer<std::uint32_t>(0, 4096);
  }
  return c;
}

/// RP_FUZZ_PRINT=1 in the environment prints each calibration (to turn a crash into a unit test).
void print(const LensCalibration& c)
{
  if (!std::getenv("RP_FUZZ_PRINT"))
  {
    return;
  }
  std::fprintf(stderr, "width %u height %u binning %u %u roi %u %u %u %u model '%s'\nK", c.width, c.height,
               c.binning_x, c.binning_y, c.roi_x_offset, c.roi_y_offset, c.roi_width, c.roi_height,
               c.distortion_model.c_str());
  for (double v : c.K) std::fprintf(stderr, " %.17g", v);
  std::fprintf(stderr, "\nP");
  for (double v : c.P) std::fprintf(stderr, " %.17g", v);
  std::fprintf(stderr, "\nD");
  for (double v : c.D) std::fprintf(stderr, " %.17g", v);
  std::fprintf(stderr, "\n");
}

/// Lenses whose round trips are meaningful in doubles: focal lengths, centre and Tx/Ty within
/// bounds where the error of a round trip stays far below the tolerances used.
bool wellConditioned(const PinholeModel& lens)
{
  return lens.fx() > 1e-3 && lens.fy() > 1e-3 && lens.fx() < 1e7 && lens.fy() < 1e7 && std::fabs(lens.cx()) < 1e7 &&
         std::fabs(lens.cy()) < 1e7 && std::fabs(lens.tx()) < 1e9 && std::fabs(lens.ty()) < 1e9;
}

bool sameModel(const PinholeModel& a, const PinholeModel& b)
{
  return a.width() == b.width() && a.height() == b.height() && a.fx() == b.fx() && a.fy() == b.fy() &&
         a.cx() == b.cx() && a.cy() == b.cy() && a.tx() == b.tx() && a.ty() == b.ty();
}
}  // namespace

void fuzzOne(Input& in);

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Input in(data, size);
  fuzzOne(in);
  return 0;
}

void fuzzOne(Input& in)
{
  const LensCalibration c = calibrationFrom(in);
  print(c);
  const PinholeModel sentinel(7, 5, 3.0, 4.0, 1.0, 2.0);
  PinholeModel lens = sentinel;
  const LensCheck check = PinholeModel::fromCalibration(c, lens);
  if (!check.ok())
  {
    RP_FUZZ_CHECK(sameModel(lens, sentinel));  // "On error `out` is left unchanged"
    RP_FUZZ_CHECK(check.error.find_first_not_of(' ') != std::string::npos);
    return;
  }
  RP_FUZZ_CHECK(lens.fx() >= PinholeModel::kMinFocalLength && lens.fy() >= PinholeModel::kMinFocalLength);
  RP_FUZZ_CHECK(lens.width() >= 1 && lens.width() <= PinholeModel::kMaxResolution);
  RP_FUZZ_CHECK(lens.height() >= 1 && lens.height() <= PinholeModel::kMaxResolution);
  RP_FUZZ_CHECK(std::isfinite(lens.fx()) && lens.fx() > 0.0);
  RP_FUZZ_CHECK(std::isfinite(lens.fy()) && lens.fy() > 0.0);
  RP_FUZZ_CHECK(std::isfinite(lens.cx()) && std::isfinite(lens.cy()));
  RP_FUZZ_CHECK(std::isfinite(lens.tx()) && std::isfinite(lens.ty()));

  // Accepted calibrations whose numbers are within sane bounds give finite rays and matrices.
  const bool sane_lens = sane(lens.fx()) && sane(lens.fy()) && sane(lens.cx()) && sane(lens.cy()) &&
                         sane(lens.tx()) && sane(lens.ty()) && lens.fx() >= 1e-6 && lens.fy() >= 1e-6;
  const Vec2 pixel = in.vec2(2000.0);
  const Vec3 ray = lens.ray(pixel);
  const Vec3 centre = lens.centre();
  const double near_clip = in.boolean() ? 0.05 : in.size(1.0);
  const double far_clip = in.boolean() ? 50.0 : in.size(100.0);
  const auto m = lens.glProjectionMatrix(near_clip, far_clip);
  if (sane_lens)
  {
    RP_FUZZ_CHECK(isFinite(centre));
    if (sane(pixel))
    {
      RP_FUZZ_CHECK(isFinite(ray) && ray.z == 1.0);
    }
    if (sane(near_clip) && sane(far_clip) && near_clip > 0.0 && far_clip > near_clip * (1.0 + 1e-9))
    {
      RP_FUZZ_CHECK(std::all_of(m.begin(), m.end(), [](double v) { return std::isfinite(v); }));
    }
    // Round trip: the pixel of a point on the ray through `pixel` (from the optical centre,
    // which Tx/Ty move) is `pixel`, at any depth.
    if (wellConditioned(lens) && std::fabs(pixel.x) < 1e5 && std::fabs(pixel.y) < 1e5)
    {
      Vec2 back;
      const double depth = in.boolean() ? 2.5 : 0.05 + std::fabs(in.number(100.0));
      if (std::isfinite(depth) && depth > 0.0 && depth < 1e6)
      {
        RP_FUZZ_CHECK(lens.project(centre + ray * depth, back));
        const double tolerance = 1e-6 * (1.0 + std::fabs(pixel.x) + std::fabs(pixel.y) + std::fabs(lens.cx()) +
                                         std::fabs(lens.cy()) + (std::fabs(lens.tx()) + std::fabs(lens.ty())) / depth);
        RP_FUZZ_CHECK(std::fabs(back.x - pixel.x) <= tolerance && std::fabs(back.y - pixel.y) <= tolerance);
      }
    }
  }
  const Vec3 point = in.vec3(10.0);
  Vec2 projected;
  if (lens.project(point, projected))
  {
    RP_FUZZ_CHECK(isFinite(projected));
    RP_FUZZ_CHECK(point.z > 0.0);
    // The other way round: the ray through the point's pixel, from the optical centre, passes
    // through the point (compared at the point's depth).
    if (sane_lens && wellConditioned(lens) && sane(point) && point.z > 1e-3 && std::fabs(point.x) < 1e3 &&
        std::fabs(point.y) < 1e3 && point.z < 1e3)
    {
      const Vec3 back = lens.centre() + lens.ray(projected) * point.z;
      const double tx = 1e-9 * (1.0 + std::fabs(point.x) + point.z +
                                (std::fabs(lens.cx()) * point.z + std::fabs(projected.x) * point.z + std::fabs(lens.tx())) / lens.fx());
      const double ty = 1e-9 * (1.0 + std::fabs(point.y) + point.z +
                                (std::fabs(lens.cy()) * point.z + std::fabs(projected.y) * point.z + std::fabs(lens.ty())) / lens.fy());
      RP_FUZZ_CHECK(std::fabs(back.x - point.x) <= tx && std::fabs(back.y - point.y) <= ty);
      RP_FUZZ_CHECK(back.z == point.z);
    }
  }

  // Footprint: the projector somewhere above (or below) the floor, any orientation.
  const double q[4] = {in.number(1.0), in.number(1.0), in.number(1.0), in.number(1.0)};
  const Vec3 position = in.vec3(5.0);
  const RigidTransform pose = RigidTransform::fromQuaternion(q[0], q[1], q[2], q[3], position);
  for (double r : pose.rotation())
  {
    RP_FUZZ_CHECK(std::isfinite(r));  // zero or NaN quaternions give the identity, never NaN
  }
  const double max_distance = in.boolean() ? 10.0 : in.size(100.0);
  const FloorFootprint footprint(lens, pose, max_distance);
  RP_FUZZ_CHECK(!std::isnan(footprint.throwDistance()));
  if (sane_lens && sane(position) && sane(max_distance) && max_distance >= 0.0)
  {
    RP_FUZZ_CHECK(isFinite(footprint.origin()));
    for (const Vec3& corner : footprint.corners())
    {
      RP_FUZZ_CHECK(isFinite(corner));
      if (footprint.complete())
      {
        RP_FUZZ_CHECK(std::fabs(corner.z) <= 1e-6 * (1.0 + std::fabs(position.z)));
      }
    }
    RP_FUZZ_CHECK(std::isfinite(footprint.width()) && footprint.width() >= 0.0);
    RP_FUZZ_CHECK(std::isfinite(footprint.depth()) && footprint.depth() >= 0.0);
  }
}
