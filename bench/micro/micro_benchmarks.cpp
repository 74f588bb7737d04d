// Microbenchmarks of rviz_projector's CPU work, each next to the reference pipeline's equivalent.
//
//   Spacer/Exact/<poses>, Spacer/Paper/<poses>   PathSpacer::space           vs Baseline/SparsePoints
//   ArrowOutline/<arrows>                         flat arrow triangles        vs Baseline/ArrowMarkers
//   PathUpdate/<poses>                            ProjectedPath's CPU update  vs Baseline/PathUpdate
//   PathUpdate+Mesh/<poses>  (mesh_benchmarks.cpp) the same + FloorMesh fill vs Baseline/PathUpdate
//
// The label "vs=<name>" names the baseline a row is compared with (same size); scripts/bench
// prints the ratio of times. Items/s are poses/s (spacer, path update) or arrows/s (outlines).
// Baselines use the reference robot's numbers (kept points >= 0.10 m apart, goal gap + 0.12 m);
// ours use the ProjectedPath display's defaults (Exact, 0.25 m) except Spacer/Paper, which uses
// the reference's numbers and is checked to keep exactly the baseline's points.
#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <tf2/buffer_core.h>

#include "bench_paths.h"
#include "reference_baseline.h"
#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/path_triangles.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace
{
using namespace rviz_projector;
namespace rb = reference_baseline;
using rviz_projector_bench::arrows;
using rviz_projector_bench::pathMessage;
using rviz_projector_bench::planarPath;

/// Display defaults, but no cap on the arrow count: every pose of the longest path is spaced.
SpacingParameters exactParameters()
{
  SpacingParameters p;
  p.max_arrows = 10000000;
  return p;
}

SpacingParameters paperParameters()
{
  const rb::Parameters reference;
  SpacingParameters p = exactParameters();
  p.mode = SpacingMode::Paper;
  p.spacing = reference.min_distance;
  p.circle_diameter = reference.circle_diameter;
  return p;
}

/// map -> odom as in demo_navigation (a fixed offset and a small rotation), in a tf2 buffer.
const tf2::BufferCore& tfBuffer()
{
  static tf2::BufferCore* buffer = [] {
    auto* core = new tf2::BufferCore();
    geometry_msgs::TransformStamped t;
    t.header.frame_id = "map";
    t.header.stamp = ros::Time(1000, 0);
    t.child_frame_id = "odom";
    t.transform.translation.x = 0.3;
    t.transform.translation.y = -0.2;
    t.transform.rotation.z = std::sin(0.5 * 0.1);
    t.transform.rotation.w = std::cos(0.5 * 0.1);
    core->setTransform(t, "bench", true);
    return core;
  }();
  return *buffer;
}

// ---- spacing -------------------------------------------------------------------------------
void spacer(benchmark::State& state, const SpacingParameters& parameters)
{
  const std::vector<Vec2>& path = planarPath(static_cast<std::size_t>(state.range(0)));
  PathSpacer spacer(parameters);
  std::size_t arrow_count = spacer.space(path).arrows.size();
  for (auto _ : state)
  {
    const SpacedPath& spaced = spacer.space(path);
    benchmark::DoNotOptimize(spaced.arrows.data());
    arrow_count = spaced.arrows.size();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["arrows"] = static_cast<double>(arrow_count);
  state.SetLabel("vs=Baseline/SparsePoints");
}

void BM_SpacerExact(benchmark::State& state)
{
  spacer(state, exactParameters());
}

void BM_SpacerPaper(benchmark::State& state)
{
  // Same input, same numbers as the baseline: the kept points must be the baseline's.
  const auto n = static_cast<std::size_t>(state.range(0));
  const std::vector<geometry_msgs::Point> kept = rb::sparsePoints(pathMessage(n).poses, rb::Parameters());
  PathSpacer check(paperParameters());
  const std::vector<Arrow>& ours = check.space(planarPath(n)).arrows;
  bool same = ours.size() == kept.size() / 2;
  for (std::size_t k = 0; same && k < ours.size(); ++k)
  {
    same = ours[k].tip.x == kept[2 * k].x && ours[k].tip.y == kept[2 * k].y && ours[k].tail.x == kept[2 * k + 1].x &&
           ours[k].tail.y == kept[2 * k + 1].y;
  }
  if (!same)
  {
    state.SkipWithError("Paper mode and the baseline keep different points");
    return;
  }
  spacer(state, paperParameters());
}

void BM_BaselineSparsePoints(benchmark::State& state)
{
  const nav_msgs::Path& path = pathMessage(static_cast<std::size_t>(state.range(0)));
  std::size_t arrow_count = 0;
  for (auto _ : state)
  {
    const std::vector<geometry_msgs::Point> kept = rb::sparsePoints(path.poses, rb::Parameters());
    benchmark::DoNotOptimize(kept.data());
    arrow_count = kept.size() / 2;
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["arrows"] = static_cast<double>(arrow_count);
}

// ---- arrow shapes --------------------------------------------------------------------------
void BM_ArrowOutline(benchmark::State& state)
{
  const std::vector<Arrow>& input = arrows(static_cast<std::size_t>(state.range(0)));
  const ArrowDimensions dimensions;
  std::vector<Vec2> triangles;
  for (auto _ : state)
  {
    ArrowOutline::trianglesOf(input, dimensions, triangles);
    benchmark::DoNotOptimize(triangles.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["arrows"] = static_cast<double>(input.size());
  state.SetLabel("vs=Baseline/ArrowMarkers");
}

void BM_BaselineArrowMarkers(benchmark::State& state)
{
  // The kept points of the reference: tip, tail, tip, tail ... as geometry_msgs points.
  const std::vector<Arrow>& input = arrows(static_cast<std::size_t>(state.range(0)));
  std::vector<geometry_msgs::Point> kept;
  for (const Arrow& arrow : input)
  {
    geometry_msgs::Point tip, tail;
    tip.x = arrow.tip.x;
    tip.y = arrow.tip.y;
    tail.x = arrow.tail.x;
    tail.y = arrow.tail.y;
    kept.push_back(tip);
    kept.push_back(tail);
  }
  for (auto _ : state)
  {
    const visualization_msgs::MarkerArray markers = rb::toMarkers(kept, rb::Parameters());
    benchmark::DoNotOptimize(markers.markers.data());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["arrows"] = static_cast<double>(input.size());
}

// ---- the whole CPU update: Path message -> mesh-ready triangles / MarkerArray -----------------
void BM_PathUpdate(benchmark::State& state)
{
  // What ProjectedPathDisplay::processMessage + rebuild + redraw do before the Ogre upload: one
  // transform for the whole path, floor points, spacing, arrow and circle triangles, all into
  // buffers kept between messages.
  const nav_msgs::Path& path = pathMessage(static_cast<std::size_t>(state.range(0)));
  const tf2::BufferCore& tf = tfBuffer();
  const SpacingParameters parameters;
  PathSpacer spacer(parameters);
  std::vector<Vec2> floor_points;
  PathTriangles triangles;
  std::size_t arrow_count = 0;
  for (auto _ : state)
  {
    const RigidTransform to_fixed = toRigidTransform(tf.lookupTransform("map", path.header.frame_id, ros::Time(0)).transform);
    pathToFloorPoints(path, to_fixed, floor_points);
    const SpacedPath& spaced = spacer.space(floor_points);
    triangles.build(spaced, parameters, PathTriangles::ArrowStyle::Flat);
    benchmark::DoNotOptimize(triangles.flatArrows().data());
    benchmark::DoNotOptimize(triangles.destination().data());
    benchmark::ClobberMemory();
    arrow_count = spaced.arrows.size();
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["arrows"] = static_cast<double>(arrow_count);
  state.SetLabel("vs=Baseline/PathUpdate");
}

void BM_BaselinePathUpdate(benchmark::State& state)
{
  const nav_msgs::Path& path = pathMessage(static_cast<std::size_t>(state.range(0)));
  const tf2::BufferCore& tf = tfBuffer();
  const rb::Parameters parameters;
  std::size_t arrow_count = 0;
  for (auto _ : state)
  {
    const std::vector<geometry_msgs::PoseStamped> poses = rb::transformPoses(path, tf, "map");
    const std::vector<geometry_msgs::Point> kept = rb::sparsePoints(poses, parameters);
    const visualization_msgs::MarkerArray markers = rb::toMarkers(kept, parameters);
    benchmark::DoNotOptimize(markers.markers.data());
    arrow_count = markers.markers.size() - 1;
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["arrows"] = static_cast<double>(arrow_count);
}
}  // namespace

BENCHMARK(BM_SpacerExact)->Name("Spacer/Exact")->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_SpacerPaper)->Name("Spacer/Paper")->RangeMultiplier(10)->Range(1000, 1000000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BaselineSparsePoints)
    ->Name("Baseline/SparsePoints")
    ->RangeMultiplier(10)
    ->Range(1000, 1000000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ArrowOutline)->Name("ArrowOutline")->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BaselineArrowMarkers)
    ->Name("Baseline/ArrowMarkers")
    ->RangeMultiplier(10)
    ->Range(100, 100000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_PathUpdate)->Name("PathUpdate")->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BaselinePathUpdate)
    ->Name("Baseline/PathUpdate")
    ->RangeMultiplier(10)
    ->Range(100, 100000)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
