// ProjectedPath's off-view cue (issue 25 part 3): deciding and drawing it for a robot somewhere along
// a 5,000-pose planner path, the lit area a 32-point outline 0.3..1.3 m ahead of the robot, 0.8 m
// wide (as FloorFootprint gives it). "Edge arrow": the robot heads 45 degrees off its path, so the
// path leaves the lit area. "Narrow strip" (near the worst case: most placements are tried and
// refused): a lit strip 0.3 m wide along the robot's heading, where an arrow clear of the path fits
// only where the path curves away. Baseline in the same run:
// the arrows of the same path (what every path update costs).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_paths.h"
#include "rviz_projector/core/off_view_cue.h"
#include "rviz_projector/core/path_location.h"

namespace
{
using namespace rviz_projector;

void offView(benchmark::State& state, bool narrow)
{
  const std::vector<Vec2>& points = rviz_projector_bench::planarPath(static_cast<std::size_t>(state.range(0)));
  std::vector<double> lengths;
  accumulateArcLengths(points, lengths);
  OffViewParameters parameters;
  if (narrow)
  {
    parameters.margin = 0.05;
    parameters.show_below = 0.99;
    parameters.hide_above = 0.99;
  }
  OffViewCue cue;
  OffViewInput input;
  double start = 0.0;
  for (auto _ : state)
  {
    start = start + 0.37 < lengths.back() - 3.0 ? start + 0.37 : 0.0;  // the robot drives on
    const double path_heading = headingAt(points, lengths, start, 0.2);
    input.robot = pointAtArcLength(points, lengths, start);
    input.heading = narrow ? path_heading : path_heading + 0.785;
    input.start = start;
    input.drawn_from = start;
    input.lit = rviz_projector_bench::litRectangle(input.robot, input.heading, 0.3, 1.3, narrow ? 0.15 : 0.4);
    benchmark::DoNotOptimize(cue.build(points, lengths, input, parameters).triangles.data());
  }
  state.counters["triangles"] = static_cast<double>(cue.result().triangles.size() / 3);
  state.SetLabel("vs=Baseline/CorridorArrows");
}

void BM_OffViewEdge(benchmark::State& state) { offView(state, false); }
void BM_OffViewNarrow(benchmark::State& state) { offView(state, true); }
}  // namespace

BENCHMARK(BM_OffViewEdge)->Name("OffView/Edge arrow")->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_OffViewNarrow)->Name("OffView/Narrow strip")->Arg(5000)->Unit(benchmark::kMicrosecond);
