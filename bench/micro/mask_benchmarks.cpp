// ProjectionMask's update for one scan (issue 15: "a 10 Hz scan of 1,000 points costs under 1 ms
// per update"): the returns to floor points in the fixed frame, the occluder columns, and the
// hand-over to the renderer (FloorMesh::setSolidTriangles into OGRE's system-memory buffers, as in
// PathUpdate+Mesh). Baseline in the same run: the returns alone (what any scan consumer pays).
#include <cmath>
#include <vector>

#include <OgreColourValue.h>
#include <OgreSceneManager.h>

#include <benchmark/benchmark.h>

#include "headless_ogre.h"
#include "rviz_projector/core/projection_mask.h"
#include "rviz_projector/displays/floor_mesh.h"

namespace
{
using namespace rviz_projector;

std::vector<float> ranges(std::size_t count)
{
  std::vector<float> r(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    r[i] = 1.0f + 0.5f * static_cast<float>(std::sin(0.01 * static_cast<double>(i)));  // a wavy wall
  }
  return r;
}

ScanView view(const std::vector<float>& r)
{
  ScanView s;
  s.angle_min = -2.35;
  s.angle_increment = 4.7 / static_cast<double>(r.size());
  s.range_min = 0.05;
  s.range_max = 10.0;
  s.ranges = r.data();
  s.count = r.size();
  return s;
}

void BM_MaskReturnsOnly(benchmark::State& state)
{
  const std::vector<float> r = ranges(static_cast<std::size_t>(state.range(0)));
  const RigidTransform pose = RigidTransform::fromQuaternion(0, 0, 0.1, 0.995, Vec3{1, 2, 0.3});
  std::vector<Vec2> points;
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(scanToFloorPoints(view(r), pose, points));
  }
}
BENCHMARK(BM_MaskReturnsOnly)->Name("MaskUpdate/returns only")->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_MaskUpdate(benchmark::State& state)
{
  const std::vector<float> r = ranges(static_cast<std::size_t>(state.range(0)));
  const RigidTransform pose = RigidTransform::fromQuaternion(0, 0, 0.1, 0.995, Vec3{1, 2, 0.3});
  Ogre::SceneManager* scene = rviz_projector_test::headlessScene();
  FloorMesh mesh(scene, scene->getRootSceneNode());
  std::vector<Vec2> points;
  OccluderMesh occluders;
  for (auto _ : state)
  {
    scanToFloorPoints(view(r), pose, points);
    occluders.build(points, 2.0, 0.1);
    mesh.setSolidTriangles(occluders.triangles(), 0.0, Ogre::ColourValue::Black);
  }
  state.counters["columns"] = static_cast<double>(occluders.columns());
}
BENCHMARK(BM_MaskUpdate)->Name("MaskUpdate+Mesh")->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond);
}  // namespace
