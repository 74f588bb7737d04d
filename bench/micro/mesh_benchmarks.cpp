// The ProjectedPath update including the hand-over to the renderer: everything of PathUpdate plus
// FloorMesh::setFlatTriangles (the vertex buffer the display draws all arrows with). OGRE runs
// without a render system or X server here: vertex buffers are OGRE's system-memory
// DefaultHardwareBufferManager, so this counts the CPU work of filling them, not the GL upload.
#include <memory>
#include <vector>

#include <OgreColourValue.h>
#include <OgreSceneManager.h>

#include <benchmark/benchmark.h>

#include "bench_paths.h"
#include "headless_ogre.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/path_triangles.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace
{
using namespace rviz_projector;

void BM_PathUpdateMesh(benchmark::State& state)
{
  const nav_msgs::Path& path = rviz_projector_bench::pathMessage(static_cast<std::size_t>(state.range(0)));
  Ogre::SceneManager* scene = rviz_projector_test::headlessScene();
  FloorMesh arrow_mesh(scene, scene->getRootSceneNode());
  FloorMesh circle_mesh(scene, scene->getRootSceneNode());
  const Ogre::ColourValue magenta(1, 0, 1, 1), green(0, 1, 0, 1);
  const SpacingParameters parameters;
  PathSpacer spacer(parameters);
  const RigidTransform to_fixed;  // the transform lookup is in PathUpdate; identity here
  std::vector<Vec2> floor_points;
  PathTriangles triangles;
  for (auto _ : state)
  {
    pathToFloorPoints(path, to_fixed, floor_points);
    triangles.build(spacer.space(floor_points), parameters, PathTriangles::ArrowStyle::Flat);
    arrow_mesh.setFlatTriangles(triangles.flatArrows(), 0.011, magenta);
    circle_mesh.setFlatTriangles(triangles.destination(), 0.01, green);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["arrows"] = static_cast<double>(arrow_mesh.triangleCount() / 3);
  state.SetLabel("vs=Baseline/PathUpdate");  // which stops at the MarkerArray: nothing drawn yet
}
}  // namespace

BENCHMARK(BM_PathUpdateMesh)->Name("PathUpdate+Mesh")->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);
