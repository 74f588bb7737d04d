// Microbenchmarks of the projector mount calibration (issue 12): solveMount on the default 3x3
// crosshair pattern and on a 10x10 one, PA503W lens, 3 mm of tape noise; and the 3x3 pattern with
// one crosshair measured 10 cm off (the outlier search fits the pose once per remaining point).
// Size: points; items/s: points/s. No baseline (the reference system had no calibration).
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "rviz_projector/core/crosshair_pattern.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/projector_mount.h"

namespace
{
using namespace rviz_projector;

const PinholeModel& lens()
{
  static const PinholeModel pa503w(1280, 800, 1900.0, 1900.0, 640.0, 817.0);
  return pa503w;
}

/// The crosshairs of a rows x cols pattern where a PA503W 1.2 m up, pitched 55 degrees down,
/// throws them, measured with 3 mm (1 sigma) of noise; the first one 10 cm off with `outlier`.
std::vector<FloorPoint> measuredPoints(int side, bool outlier)
{
  const RigidTransform pose = opticalPoseOfMount({0.15, 0.0, 1.2, 0.0, 55.0 * M_PI / 180.0, 0.0});
  std::mt19937 rng(12);
  std::normal_distribution<double> noise(0.0, 0.003);
  std::vector<FloorPoint> points;
  for (const Crosshair& c : crosshairPattern(lens().width(), lens().height(), side, side))
  {
    Vec3 w;
    if (pixelOnPlane(lens(), pose, c.pixel, 0.0, w))
    {
      points.push_back({c.id, c.pixel, {w.x + noise(rng), w.y + noise(rng), 0.0}});
    }
  }
  if (outlier && !points.empty())
  {
    points.front().world.x += 0.1;
  }
  return points;
}

void solve(benchmark::State& state, bool outlier)
{
  const std::vector<FloorPoint> points = measuredPoints(static_cast<int>(std::lround(std::sqrt(state.range(0)))), outlier);
  if (static_cast<std::int64_t>(points.size()) != state.range(0) || !solveMount(lens(), points).ok)
  {
    state.SkipWithError("synthetic calibration points did not solve");
    return;
  }
  for (auto _ : state)
  {
    MountSolution s = solveMount(lens(), points);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
}

void BM_MountSolve(benchmark::State& state) { solve(state, false); }
void BM_MountSolveOutlier(benchmark::State& state) { solve(state, true); }
}  // namespace

BENCHMARK(BM_MountSolve)->Name("MountSolve")->Arg(9)->Arg(100)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_MountSolveOutlier)->Name("MountSolve+Outlier")->Arg(9)->Unit(benchmark::kMicrosecond);
