// ProjectedPath with every cue on (issue 25: "the micro and e2e benchmarks show the cost with
// everything on"): one frame of a robot driving along a 5,000-pose planner path, with the horizon,
// marching (re-spaced every frame), the turn signal, the stop zone at 0.5 m/s, the corridor of a
// rectangular robot over 3 m and the off-view cue (the lit area 0.3..1.3 m ahead, the robot
// heading 45 degrees off its path: a cue is drawn). "Speed-coded" also re-spaces the arrows by speed
// every frame instead of marching. Baseline in the same run: the arrows of the same path, spaced and
// turned into triangles (what every path update costs without cues).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_paths.h"
#include "rviz_projector/core/cue_drawing.h"
#include "rviz_projector/core/marching.h"
#include "rviz_projector/core/off_view_cue.h"
#include "rviz_projector/core/path_location.h"
#include "rviz_projector/core/path_spacer.h"

namespace
{
using namespace rviz_projector;

void everything(benchmark::State& state, bool speed_coded)
{
  const std::vector<Vec2>& points = rviz_projector_bench::planarPath(static_cast<std::size_t>(state.range(0)));
  std::vector<double> lengths;
  accumulateArcLengths(points, lengths);
  SpacingParameters spacing;
  PathSpacer spacer(spacing);
  PathCueSettings settings;
  settings.horizon = true;
  settings.marching = !speed_coded;
  settings.turn_signal = true;
  settings.stop_zone = true;
  settings.corridor = true;
  settings.corridor_parameters.length = 3.0;
  settings.corridor_radius = 0.0;
  settings.corridor_footprint = {{0.4, 0.3}, {-0.2, 0.3}, {-0.2, -0.3}, {0.4, -0.3}};
  PathCueInput input;
  input.robot_known = true;
  input.speed.speed = 0.5;
  input.speed.moving = true;
  CueDrawing cues;
  OffViewCue off_view;
  OffViewParameters off_view_parameters;
  OffViewInput off_view_input;
  double start = 0.0;
  double time = 0.0;
  for (auto _ : state)
  {
    start = start + 0.37 < lengths.back() - 3.0 ? start + 0.37 : 0.0;  // the robot drives on
    time += 1.0 / 60.0;
    input.time = time;
    input.robot = pointAtArcLength(points, lengths, start);
    if (speed_coded)
    {
      spacing.speed_coding.enabled = true;
      spacing.speed_coding.speed = 0.5 + 0.01 * std::fmod(time, 1.0);  // a new speed every frame
      spacer.setParameters(spacing);
    }
    const SpacedPath& spaced =
        spacer.space(points, speed_coded ? 0.0 : marchingPhase(settings.marching_speed, time, spacing.spacing));
    cues.build(points, spaced, spacer.parameters(), settings, input);
    off_view_input.robot = input.robot;
    off_view_input.heading = headingAt(points, lengths, start, 0.2) + 0.785;
    off_view_input.start = start;
    off_view_input.drawn_from = cues.horizonStart();
    off_view_input.lit = rviz_projector_bench::litRectangle(off_view_input.robot, off_view_input.heading, 0.3, 1.3, 0.4);
    benchmark::DoNotOptimize(off_view.build(points, lengths, off_view_input, off_view_parameters).triangles.data());
    benchmark::DoNotOptimize(cues.arrows().data());
  }
  state.counters["arrow triangles"] = static_cast<double>(cues.arrows().size() / 3);
  state.counters["corridor triangles"] = static_cast<double>(cues.corridor().edges().size() / 3);
  state.counters["stop zone triangles"] = static_cast<double>(cues.stopZone().triangles().size() / 3);
  state.SetLabel("vs=Baseline/CorridorArrows");
}

void BM_CuesEverything(benchmark::State& state) { everything(state, false); }
void BM_CuesEverythingSpeedCoded(benchmark::State& state) { everything(state, true); }
}  // namespace

BENCHMARK(BM_CuesEverything)->Name("Cues/Everything on")->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_CuesEverythingSpeedCoded)->Name("Cues/Everything on, speed-coded")->Arg(5000)->Unit(benchmark::kMicrosecond);
