// ProjectionMask's update for one scan (issue 15: "a 10 Hz scan of 1,000 points costs under 1 ms
// per update"): the returns to floor points in the fixed frame, the occluder columns, and the
// hand-over to the renderer (FloorMesh::setSolidTriangles into OGRE's system-memory buffers, as in
// PathUpdate+Mesh). Baseline in the same run: the returns alone (what any scan consumer pays).
// MaskCloud: a depth camera's 640x480 PointCloud2 (a person-sized blob in front of a wall, padded
// rows) read, moved to the fixed frame, filtered by height, thinned to cells and meshed; baseline:
// reading the cloud alone.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include <OgreColourValue.h>
#include <OgreSceneManager.h>

#include <benchmark/benchmark.h>

#include "headless_ogre.h"
#include "rviz_projector/core/occluder_union.h"
#include "rviz_projector/core/projection_mask.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/ros/ros_conversions.h"

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

/// A scan's returns -> occluders -> the OGRE mesh: OccluderMesh's columns (the baseline, and what
/// is drawn beyond OccluderUnion::kMaxSquares returns) or, `merged`, their union drawn once
/// (OccluderUnion: what the display draws up to that many).
void maskUpdate(benchmark::State& state, bool merged)
{
  const std::vector<float> r = ranges(static_cast<std::size_t>(state.range(0)));
  const RigidTransform pose = RigidTransform::fromQuaternion(0, 0, 0.1, 0.995, Vec3{1, 2, 0.3});
  Ogre::SceneManager* scene = rviz_projector_test::headlessScene();
  FloorMesh mesh(scene, scene->getRootSceneNode());
  std::vector<Vec2> points;
  OccluderMesh occluders;
  OccluderUnion solid;
  for (auto _ : state)
  {
    scanToFloorPoints(view(r), pose, points);
    if (merged)
    {
      benchmark::DoNotOptimize(solid.build({{&points, 0.1}}, 2.0));
    }
    else
    {
      occluders.build(points, 2.0, 0.1);
    }
    mesh.setSolidTriangles(merged ? solid.triangles() : occluders.triangles(), 0.0, Ogre::ColourValue::Black);
  }
  state.counters[merged ? "triangles" : "columns"] =
      static_cast<double>(merged ? solid.triangles().size() / 3 : occluders.columns());
}
BENCHMARK_CAPTURE(maskUpdate, columns, false)->Name("MaskUpdate+Mesh")->Arg(1000)->Arg(5000)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(maskUpdate, union, true)
    ->Name("MaskUpdate+Union+Mesh")
    ->Arg(50)
    ->Arg(100)
    ->Arg(200)
    ->Unit(benchmark::kMicrosecond);

/// `points` / 640 rows of 640 points (a 640x480 depth camera: 307200), x y z float + 4 bytes of
/// intensity, rows padded by 16 bytes: a wall 3 m ahead (x forward), 2.4 m wide, 0..1.8 m high,
/// with a person-sized blob 1.5 m ahead in the middle.
sensor_msgs::PointCloud2 depthCloud(std::int64_t points)
{
  sensor_msgs::PointCloud2 cloud;
  cloud.width = 640;
  cloud.height = static_cast<std::uint32_t>(points / 640);
  cloud.point_step = 16;
  cloud.row_step = cloud.width * cloud.point_step + 16;
  const char* names[] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis)
  {
    sensor_msgs::PointField f;
    f.name = names[axis];
    f.offset = static_cast<std::uint32_t>(4 * axis);
    f.datatype = sensor_msgs::PointField::FLOAT32;
    f.count = 1;
    cloud.fields.push_back(f);
  }
  cloud.data.assign(std::size_t(cloud.row_step) * cloud.height, 0);
  for (std::uint32_t r = 0; r < cloud.height; ++r)
  {
    for (std::uint32_t c = 0; c < cloud.width; ++c)
    {
      const float y = 1.2f - 2.4f * static_cast<float>(c) / 640.0f;
      const float z = 1.8f - 1.8f * static_cast<float>(r) / static_cast<float>(cloud.height);
      const float x = std::abs(y) < 0.25f && z > 0.05f ? 1.5f : 3.0f;
      const float xyz[3] = {x, y, z};
      std::memcpy(cloud.data.data() + std::size_t(r) * cloud.row_step + std::size_t(c) * cloud.point_step, xyz,
                  sizeof(xyz));
    }
  }
  return cloud;
}

void BM_MaskCloudReadOnly(benchmark::State& state)
{
  const sensor_msgs::PointCloud2 cloud = depthCloud(state.range(0));
  std::vector<Vec3> xyz;
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(readCloudXyz(cloud, xyz));
  }
}
BENCHMARK(BM_MaskCloudReadOnly)->Name("MaskCloud/read only")->Arg(640 * 480)->Unit(benchmark::kMillisecond);

void BM_MaskCloud(benchmark::State& state)
{
  const sensor_msgs::PointCloud2 cloud = depthCloud(state.range(0));
  const RigidTransform pose = RigidTransform::fromQuaternion(0, 0, 0.1, 0.995, Vec3{1, 2, 0.3});
  Ogre::SceneManager* scene = rviz_projector_test::headlessScene();
  FloorMesh mesh(scene, scene->getRootSceneNode());
  std::vector<Vec3> xyz, fixed;
  std::vector<Vec2> points;
  OccluderMesh occluders;
  for (auto _ : state)
  {
    readCloudXyz(cloud, xyz);
    fixed.clear();
    for (const Vec3& p : xyz)
    {
      fixed.push_back(pose.apply(p));
    }
    points.clear();
    cloudToFloorPoints(fixed, 0.03, 2.0, points);
    snapToCells(points, 0.1, 20000);
    occluders.build(points, 2.0, 0.15);
    mesh.setSolidTriangles(occluders.triangles(), 0.0, Ogre::ColourValue::Black);
  }
  state.counters["columns"] = static_cast<double>(occluders.columns());
}
BENCHMARK(BM_MaskCloud)->Name("MaskCloud+Mesh")->Arg(640 * 480)->Unit(benchmark::kMillisecond);
}  // namespace
