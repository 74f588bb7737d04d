// ProjectionMask's Acknowledge cue (issue 25, part 4), what one scan costs: a 1,080-beam scan (a
// 270 degree scanner at 0.25 degrees) of a room's walls with 5 people in it, clustered
// (findPersonClusters), associated with the people of the scan before (PersonTracker, the people
// walking 0.1 m a scan) and an arc built for each near a 5,000-pose planner path (acknowledgeArc).
#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_paths.h"
#include "rviz_projector/core/acknowledge_arc.h"
#include "rviz_projector/core/person_clusters.h"
#include "rviz_projector/core/person_tracker.h"

namespace
{
using namespace rviz_projector;

/// The scan's floor points: a square room 8 m across around the scanner, people (0.4 m wide
/// arcs of returns) at `people`, in beam order.
void scanPoints(const std::vector<Vec2>& people, std::vector<Vec2>& points)
{
  points.clear();
  const int beams = 1080;
  for (int i = 0; i < beams; ++i)
  {
    const double a = -0.75 * M_PI + 1.5 * M_PI * i / (beams - 1);
    const Vec2 d{std::cos(a), std::sin(a)};
    double range = 4.0 / std::max(std::abs(d.x), std::abs(d.y));  // the walls
    for (const Vec2& p : people)
    {
      const double along = dot(p, d);
      const double off = std::abs(d.x * p.y - d.y * p.x);
      if (along > 0.0 && off < 0.2 && along - 0.1 < range)
      {
        range = along - 0.1;
      }
    }
    points.push_back(d * range);
  }
}

void BM_AcknowledgeScan(benchmark::State& state)
{
  const std::vector<Vec2>& path = rviz_projector_bench::planarPath(static_cast<std::size_t>(state.range(0)));
  std::vector<Vec2> people{{1.5, 0.5}, {2.0, -0.8}, {-1.0, 1.5}, {3.0, 2.0}, {1.0, -2.5}};
  std::vector<Vec2> points;
  std::vector<PersonCluster> clusters;
  std::vector<Vec2> triangles;
  PersonTracker tracker;
  const ClusterLimits limits;
  const TrackerParameters tracking;
  const AcknowledgeParameters arc;
  double time = 0.0;
  std::size_t drawn = 0;
  for (auto _ : state)
  {
    state.PauseTiming();
    for (Vec2& p : people)
    {
      p.x += 0.1;
      if (p.x > 3.5)
      {
        p.x = -3.5;
      }
    }
    scanPoints(people, points);
    state.ResumeTiming();
    time += 0.1;
    findPersonClusters(points, limits, clusters);
    tracker.update(clusters, time, tracking);
    triangles.clear();
    drawn = 0;
    const PathAheadStart start = locatePathAhead(path, path.front());
    for (const PersonTrack& t : tracker.tracks())
    {
      drawn += acknowledgeArc(t.position, t.radius + 0.14, path.front(), path, start, arc, triangles).drawn ? 1 : 0;
    }
    benchmark::DoNotOptimize(triangles.data());
  }
  state.counters["people"] = static_cast<double>(tracker.tracks().size());
  state.counters["arcs"] = static_cast<double>(drawn);
}
}  // namespace

BENCHMARK(BM_AcknowledgeScan)->Name("Acknowledge/Scan 1080 beams, 5 people")->Arg(100)->Arg(5000)->Unit(benchmark::kMicrosecond);
