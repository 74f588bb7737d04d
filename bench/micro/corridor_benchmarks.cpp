// ProjectedPath's corridor (issue 25: "costs no more than the arrows do; a 5,000-pose path at 20 Hz
// stays within the existing frame budget"): the swept corridor of a rectangular and of a round robot
// over the next 3 m of a planner's path, rebuilt for a robot somewhere along it. Baseline in the same
// run: the arrows of the same path, spaced and turned into triangles (what every path update costs).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_paths.h"
#include "rviz_projector/core/path_location.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/path_triangles.h"
#include "rviz_projector/core/swept_corridor.h"

namespace
{
using namespace rviz_projector;

void BM_CorridorArrowsBaseline(benchmark::State& state)
{
  const std::vector<Vec2>& points = rviz_projector_bench::planarPath(static_cast<std::size_t>(state.range(0)));
  const SpacingParameters parameters;
  PathSpacer spacer(parameters);
  PathTriangles triangles;
  for (auto _ : state)
  {
    triangles.build(spacer.space(points), parameters, PathTriangles::ArrowStyle::Flat);
    benchmark::DoNotOptimize(triangles.flatArrows().data());
  }
}

enum class Shape
{
  Rectangle,
  Circle24,  // a round robot's footprint as move_base publishes it (and the demo): a 24-gon
  Round
};

void corridor(benchmark::State& state, Shape shape, bool straight = false)
{
  std::vector<Vec2> line;  // a straight aisle of the same number of poses, 2 cm apart
  for (std::size_t i = 0; straight && i < static_cast<std::size_t>(state.range(0)); ++i)
  {
    line.push_back({0.02 * double(i), 0.0});
  }
  const std::vector<Vec2>& points =
      straight ? line : rviz_projector_bench::planarPath(static_cast<std::size_t>(state.range(0)));
  std::vector<double> lengths;
  accumulateArcLengths(points, lengths);
  std::vector<Vec2> footprint{{0.4, 0.3}, {-0.2, 0.3}, {-0.2, -0.3}, {0.4, -0.3}};
  if (shape == Shape::Circle24)
  {
    footprint.clear();
    for (int i = 0; i < 24; ++i)
    {
      footprint.push_back({0.3 * std::cos(2.0 * M_PI * i / 24), 0.3 * std::sin(2.0 * M_PI * i / 24)});
    }
  }
  CorridorParameters parameters;
  parameters.length = 3.0;
  SweptCorridor swept;
  double start = 0.0;
  for (auto _ : state)
  {
    start = start + 0.37 < lengths.back() - 3.0 ? start + 0.37 : 0.0;  // the robot drives on
    if (shape == Shape::Round)
    {
      swept.buildRound(points, lengths, start, 0.3, parameters);
    }
    else
    {
      swept.build(points, lengths, start, footprint, parameters);
    }
    benchmark::DoNotOptimize(swept.edges().data());
  }
  state.counters["band triangles"] = static_cast<double>(swept.band().size() / 3);
  state.counters["edge triangles"] = static_cast<double>(swept.edges().size() / 3);
  state.SetLabel("vs=Baseline/CorridorArrows");
}

void BM_CorridorPolygon(benchmark::State& state) { corridor(state, Shape::Rectangle); }
void BM_CorridorCircle24(benchmark::State& state) { corridor(state, Shape::Circle24); }
void BM_CorridorRound(benchmark::State& state) { corridor(state, Shape::Round); }
void BM_CorridorCircle24Straight(benchmark::State& state) { corridor(state, Shape::Circle24, true); }
}  // namespace

BENCHMARK(BM_CorridorArrowsBaseline)->Name("Baseline/CorridorArrows")->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CorridorPolygon)->Name("Corridor/Rectangle 3 m")->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CorridorCircle24)->Name("Corridor/24-gon 3 m")->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CorridorCircle24Straight)->Name("Corridor/24-gon 3 m, straight")->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CorridorRound)->Name("Corridor/Round 3 m")->Arg(5000)->Unit(benchmark::kMicrosecond);
