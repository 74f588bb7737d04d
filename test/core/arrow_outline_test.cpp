// ArrowOutline, ArrowSolid and DiscOutline: the shapes drawn on the floor.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rviz_projector/core/arrow_outline.h"
#include "rviz_projector/core/arrow_solid.h"
#include "rviz_projector/core/disc_outline.h"

using rviz_projector::Arrow;
using rviz_projector::ArrowDimensions;
using rviz_projector::ArrowOutline;
using rviz_projector::ArrowSolid;
using rviz_projector::DiscOutline;
using rviz_projector::MeshVertex;
using rviz_projector::Vec2;

namespace
{
ArrowDimensions dimensions()
{
  ArrowDimensions d;
  d.shaft_length = 0.1;
  d.shaft_diameter = 0.04;
  d.head_length = 0.08;
  d.head_diameter = 0.12;
  return d;
}

double triangleArea(const Vec2& a, const Vec2& b, const Vec2& c)
{
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}
}  // namespace

TEST(ArrowOutline, CornersOfAnArrowAlongX)
{
  const ArrowOutline o(Arrow{{0.0, 0.0}, {0.18, 0.0}}, dimensions());
  ASSERT_TRUE(o.valid());
  const auto& c = o.corners();
  EXPECT_NEAR(c[0].x, 0.0, 1e-12);
  EXPECT_NEAR(c[0].y, -0.02, 1e-12);
  EXPECT_NEAR(c[1].x, 0.10, 1e-12);  // neck: tip - head length
  EXPECT_NEAR(c[2].y, -0.06, 1e-12);
  EXPECT_NEAR(c[3].x, 0.18, 1e-12);
  EXPECT_NEAR(c[4].y, 0.06, 1e-12);
  EXPECT_NEAR(c[6].y, 0.02, 1e-12);
}

TEST(ArrowOutline, TrianglesAreCounterClockwiseAndCoverTheArea)
{
  const ArrowOutline o(Arrow{{1.0, 1.0}, {1.0, 1.18}}, dimensions());  // pointing +y
  std::vector<Vec2> tris;
  o.appendTriangles(tris);
  ASSERT_EQ(tris.size(), ArrowOutline::kVerticesPerArrow);
  double area = 0.0;
  for (std::size_t i = 0; i < tris.size(); i += 3)
  {
    const double a = triangleArea(tris[i], tris[i + 1], tris[i + 2]);
    EXPECT_GT(a, 0.0) << "triangle " << i / 3 << " must face up";
    area += a;
  }
  EXPECT_NEAR(area, 0.10 * 0.04 + 0.5 * 0.08 * 0.12, 1e-12);
  EXPECT_TRUE(o.contains({1.0, 1.05}));
  EXPECT_TRUE(o.contains({1.05, 1.11}));   // head is wider than the shaft
  EXPECT_FALSE(o.contains({1.05, 1.05}));  // beside the shaft
  EXPECT_FALSE(o.contains({1.0, 1.2}));    // beyond the tip
}

TEST(ArrowOutline, ShortArrowIsAllHeadAndZeroLengthHasNoShape)
{
  const ArrowOutline short_arrow(Arrow{{0.0, 0.0}, {0.05, 0.0}}, dimensions());
  EXPECT_NEAR(short_arrow.corners()[1].x, 0.0, 1e-12);  // neck at the tail
  const ArrowOutline none(Arrow{{0.3, 0.3}, {0.3, 0.3}}, dimensions());
  EXPECT_FALSE(none.valid());
  std::vector<Vec2> tris;
  none.appendTriangles(tris);
  EXPECT_TRUE(tris.empty());
}

TEST(ArrowOutline, TrianglesOfAPathReplaceTheBufferAndSkipShapelessArrows)
{
  const std::vector<Arrow> arrows{{{0.0, 0.0}, {0.18, 0.0}}, {{0.3, 0.3}, {0.3, 0.3}}, {{1.0, 1.0}, {1.0, 1.18}}};
  std::vector<Vec2> tris(5, Vec2{9.0, 9.0});  // left over from the previous path
  ArrowOutline::trianglesOf(arrows, dimensions(), tris);
  ASSERT_EQ(tris.size(), 2 * ArrowOutline::kVerticesPerArrow);
  std::vector<Vec2> second;
  ArrowOutline(arrows[2], dimensions()).appendTriangles(second);
  for (std::size_t i = 0; i < second.size(); ++i)
  {
    EXPECT_EQ(tris[ArrowOutline::kVerticesPerArrow + i].x, second[i].x);
    EXPECT_EQ(tris[ArrowOutline::kVerticesPerArrow + i].y, second[i].y);
  }
  std::vector<MeshVertex> mesh(3);
  ArrowSolid::trianglesOf(arrows, dimensions(), mesh);
  EXPECT_EQ(mesh.size(), 2 * ArrowSolid::kVerticesPerArrow);
  ArrowOutline::trianglesOf({}, dimensions(), tris);
  EXPECT_TRUE(tris.empty());
}

TEST(ArrowSolid, MeshRestsOnTheFloorWithOutwardNormals)
{
  const ArrowDimensions d = dimensions();
  const ArrowSolid s(Arrow{{0.0, 0.0}, {0.18, 0.0}}, d);
  std::vector<MeshVertex> mesh;
  s.appendTriangles(mesh);
  ASSERT_EQ(mesh.size(), ArrowSolid::kVerticesPerArrow);
  double min_z = 1e9, max_x = -1e9;
  for (const MeshVertex& v : mesh)
  {
    min_z = std::min(min_z, v.position.z);
    max_x = std::max(max_x, v.position.x);
    EXPECT_NEAR(rviz_projector::norm(v.normal), 1.0, 1e-9);
  }
  EXPECT_NEAR(min_z, 0.0, 1e-12);
  EXPECT_NEAR(max_x, 0.18, 1e-12);
  // Winding agrees with the normals: each face's geometric normal points the same way.
  for (std::size_t i = 0; i < mesh.size(); i += 3)
  {
    const auto e1 = mesh[i + 1].position - mesh[i].position;
    const auto e2 = mesh[i + 2].position - mesh[i].position;
    const auto face = rviz_projector::cross(e1, e2);
    const auto n = mesh[i].normal + mesh[i + 1].normal + mesh[i + 2].normal;
    EXPECT_GT(rviz_projector::dot(face, n), 0.0) << "triangle " << i / 3;
  }
}

TEST(DiscOutline, FanCoversTheDisc)
{
  const DiscOutline disc({2.0, -1.0}, 0.4, 64);
  std::vector<Vec2> tris;
  disc.appendTriangles(tris);
  ASSERT_EQ(tris.size(), 64u * 3);
  double area = 0.0;
  for (std::size_t i = 0; i < tris.size(); i += 3)
  {
    area += triangleArea(tris[i], tris[i + 1], tris[i + 2]);
  }
  EXPECT_NEAR(area, M_PI * 0.04, 0.002);
  EXPECT_TRUE(disc.contains({2.19, -1.0}));
  EXPECT_FALSE(disc.contains({2.21, -1.0}));
  tris.clear();
  DiscOutline({0, 0}, 0.0).appendTriangles(tris);
  EXPECT_TRUE(tris.empty());
}
