// libFuzzer target: the calibration core (issue 12). crosshairPattern / crosshairPatternRects for
// any image size and rows/cols, then floorPointsProblem + solveMount on points that are partly a
// plausible measurement (a mount, the pattern's pixels, their floor points) and partly nasty
// numbers (NaN/Inf, huge, duplicate ids, collinear, millimetres). Invariants: no crash or UB; the
// pattern lies inside the image and its rectangles too; solveMount either refuses with a message
// (ok == false, error non-empty) or returns a finite mount, finite non-negative residuals (one per
// input point, in order), outliers that are input ids, and finite non-negative expected errors;
// when floorPointsProblem refuses the input, solveMount refuses it too.
#include <cstddef>
#include <cstdint>
#include <set>
#include <vector>

#include "fuzz_input.h"
#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/projector_mount.h"

using namespace rviz_projector;
using rviz_projector_fuzz::Input;

namespace
{
void checkPattern(Input& in)
{
  const std::uint32_t width = in.boolean() ? in.integer<std::uint32_t>(0, 5000) : in.integer<std::uint32_t>();
  const std::uint32_t height = in.boolean() ? in.integer<std::uint32_t>(0, 5000) : in.integer<std::uint32_t>();
  const int rows = in.integer<int>(-2, 14);
  const int cols = in.integer<int>(-2, 14);
  const std::vector<Crosshair> pattern = crosshairPattern(width, height, rows, cols);
  RP_FUZZ_CHECK(pattern.empty() == !crosshairPatternProblem(width, height, rows, cols).empty());
  if (pattern.empty() || width > 5000 || height > 5000)
  {
    return;  // the rectangles of a huge image are many; the sizes above cover the logic
  }
  RP_FUZZ_CHECK(static_cast<int>(pattern.size()) == rows * cols);
  for (const Crosshair& c : pattern)
  {
    RP_FUZZ_CHECK(c.pixel.x >= 0.0 && c.pixel.x <= width - 1.0 && c.pixel.y >= 0.0 && c.pixel.y <= height - 1.0);
  }
  for (const PatternRect& r : crosshairPatternRects(pattern, width, height))
  {
    RP_FUZZ_CHECK(r.x0 < r.x1 && r.y0 < r.y1);
    RP_FUZZ_CHECK(r.x0 >= -0.5 && r.y0 >= -0.5 && r.x1 <= width - 0.5 && r.y1 <= height - 0.5);
  }
}

void checkSolver(Input& in)
{
  PinholeModel lens(1280, 800, 1900.0, 1900.0, 639.5, 817.0);
  if (in.boolean())
  {
    lens = PinholeModel(in.integer<std::uint32_t>(16, 4000), in.integer<std::uint32_t>(16, 4000), in.number(5000.0),
                        in.number(5000.0), in.number(3000.0), in.number(3000.0));
  }
  ProjectorMount mount;
  mount.x = in.number(1.0);
  mount.y = in.number(1.0);
  mount.z = in.number(3.0);
  mount.roll = in.number(0.5);
  mount.pitch = in.number(2.0);
  mount.yaw = in.number(4.0);
  const RigidTransform pose = opticalPoseOfMount(mount);
  std::vector<FloorPoint> points;
  const std::vector<Crosshair> pattern = crosshairPattern(lens.width(), lens.height(), in.integer<int>(1, 5),
                                                          in.integer<int>(1, 5));
  for (const Crosshair& c : pattern)
  {
    FloorPoint p;
    p.id = c.id;
    p.pixel = c.pixel;
    if (!pixelOnPlane(lens, pose, c.pixel, 0.0, p.world))
    {
      p.world = in.vec3(10.0);
    }
    const int damage = in.integer<int>(0, 9);
    if (damage == 0)
    {
      p.world = in.vec3(100.0);  // anything, incl. NaN, Inf, millimetres
    }
    else if (damage == 1)
    {
      p.pixel = in.vec2(5000.0);
    }
    else if (damage == 2)
    {
      p.id = in.integer<int>(-1, 3);  // duplicates
    }
    else if (damage == 3)
    {
      p.world.x += in.number(0.2);  // noise or an outlier
      p.world.y += in.number(0.2);
    }
    points.push_back(p);
  }
  while (!in.empty() && points.size() < 40 && in.boolean())
  {
    points.push_back({in.integer<int>(-5, 60), in.vec2(3000.0), in.vec3(20.0)});
  }
  MountSolverOptions options;
  if (in.boolean())
  {
    options.tape_error = in.number(0.01);
    options.outlier_distance = in.number(0.1);
  }
  options.fit_intrinsics = in.integer<int>(0, 7) == 0;
  const std::string problem = floorPointsProblem(lens, points);
  const MountSolution s = solveMount(lens, points, options);
  if (!problem.empty())
  {
    RP_FUZZ_CHECK(!s.ok);
  }
  if (!s.ok)
  {
    RP_FUZZ_CHECK(!s.error.empty());
    return;
  }
  RP_FUZZ_CHECK(std::isfinite(s.mount.x) && std::isfinite(s.mount.y) && std::isfinite(s.mount.z));
  RP_FUZZ_CHECK(std::isfinite(s.mount.roll) && std::isfinite(s.mount.pitch) && std::isfinite(s.mount.yaw));
  RP_FUZZ_CHECK(std::isfinite(s.rms_px) && s.rms_px >= 0.0 && std::isfinite(s.rms_mm) && s.rms_mm >= 0.0);
  RP_FUZZ_CHECK(s.residuals.size() == points.size());
  std::set<int> ids;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    ids.insert(points[i].id);
    RP_FUZZ_CHECK(s.residuals[i].id == points[i].id);
    RP_FUZZ_CHECK(s.residuals[i].px >= 0.0 && s.residuals[i].mm >= 0.0);
  }
  for (int id : s.outliers)
  {
    RP_FUZZ_CHECK(ids.count(id) == 1);
  }
  for (const ExpectedError& e : s.expected)
  {
    RP_FUZZ_CHECK(std::isfinite(e.mm) && e.mm >= 0.0);
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Input in(data, size);
  if (in.boolean())
  {
    checkPattern(in);
  }
  else
  {
    checkSolver(in);
  }
  return 0;
}
