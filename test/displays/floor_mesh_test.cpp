// FloorMesh, the batched mesh both displays draw with, on a headless OGRE: the vertices, colours
// and bounds that reach the vertex buffer, and that a new path reuses the buffer instead of
// allocating one.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include <OgreColourValue.h>
#include <OgrePass.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>

#include "headless_ogre.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/displays/floor_mesh_renderable.h"

using rviz_projector::FloorMesh;
using rviz_projector::FloorMeshRenderable;
using rviz_projector::MeshVertex;
using rviz_projector::Vec2;

namespace
{
class FloorMeshTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    scene_ = rviz_projector_test::headlessScene();
    parent_ = scene_->getRootSceneNode()->createChildSceneNode();
    mesh_ = std::make_unique<FloorMesh>(scene_, parent_);
  }
  void TearDown() override
  {
    mesh_.reset();
    scene_->destroySceneNode(parent_);
    // OGRE deletes the passes of removed materials when it next renders a frame; nothing renders
    // here, so do it as a frame would (else LeakSanitizer reports them).
    Ogre::Pass::processPendingPassUpdates();
  }

  /// The renderable FloorMesh attached below our parent node.
  FloorMeshRenderable& renderable()
  {
    auto* node = static_cast<Ogre::SceneNode*>(parent_->getChild(0));
    return *static_cast<FloorMeshRenderable*>(node->getAttachedObject(0));
  }

  /// The floats of the vertices currently drawn, read back from the vertex buffer.
  std::vector<float> vertexFloats()
  {
    Ogre::RenderOperation op;
    renderable().getRenderOperation(op);
    const Ogre::HardwareVertexBufferSharedPtr buffer = op.vertexData->vertexBufferBinding->getBuffer(0);
    const std::size_t bytes = op.vertexData->vertexCount * buffer->getVertexSize();
    std::vector<float> out(bytes / sizeof(float));
    if (bytes > 0)
    {
      buffer->readData(0, bytes, out.data());
    }
    return out;
  }

  /// Two triangles per unit square along x, `squares` of them: a path's worth of triangles.
  static std::vector<Vec2> strip(std::size_t squares)
  {
    std::vector<Vec2> t;
    for (std::size_t i = 0; i < squares; ++i)
    {
      const double x = static_cast<double>(i);
      t.insert(t.end(), {{x, 0}, {x + 1, 0}, {x + 1, 1}, {x, 0}, {x + 1, 1}, {x, 1}});
    }
    return t;
  }

  Ogre::SceneManager* scene_ = nullptr;
  Ogre::SceneNode* parent_ = nullptr;
  std::unique_ptr<FloorMesh> mesh_;
};

TEST_F(FloorMeshTest, FlatTrianglesReachTheBufferWithHeightColourAndBounds)
{
  const Ogre::ColourValue magenta(1, 0, 1, 1);
  mesh_->setFlatTriangles({{1.0, 2.0}, {3.0, 2.0}, {3.0, -4.0}}, 0.25, magenta);
  EXPECT_EQ(mesh_->triangleCount(), 1u);
  EXPECT_TRUE(renderable().isVisible());
  const std::vector<float> f = vertexFloats();
  ASSERT_EQ(f.size(), 3u * FloorMeshRenderable::floatsPerVertex(FloorMeshRenderable::Layout::PositionColour));
  EXPECT_FLOAT_EQ(f[0], 1.0f);
  EXPECT_FLOAT_EQ(f[1], 2.0f);
  EXPECT_FLOAT_EQ(f[2], 0.25f);
  EXPECT_FLOAT_EQ(f[8], 3.0f);
  EXPECT_FLOAT_EQ(f[9], -4.0f);
  std::uint32_t packed = 0;
  std::memcpy(&packed, &f[3], sizeof packed);
  EXPECT_EQ(packed, Ogre::VertexElement::convertColourValue(magenta, Ogre::VertexElement::getBestColourVertexElementType()));
  const Ogre::AxisAlignedBox box = renderable().getBoundingBox();
  EXPECT_EQ(box.getMinimum(), Ogre::Vector3(1.0f, -4.0f, 0.25f));
  EXPECT_EQ(box.getMaximum(), Ogre::Vector3(3.0f, 2.0f, 0.25f));
}

TEST_F(FloorMeshTest, ANewPathReusesTheBufferAndOnlyGrowingReallocates)
{
  const Ogre::ColourValue green(0, 1, 0, 1);
  mesh_->setFlatTriangles(strip(100), 0.0, green);  // 600 vertices: the smallest buffer
  EXPECT_EQ(mesh_->bufferAllocations(), 1u);
  for (std::size_t squares : {150u, 20u, 170u, 1u})
  {
    mesh_->setFlatTriangles(strip(squares), 0.0, green);
    EXPECT_EQ(mesh_->triangleCount(), 2 * squares);
    EXPECT_EQ(vertexFloats().size(), 6 * squares * 4);
  }
  EXPECT_EQ(mesh_->bufferAllocations(), 1u) << "paths that fit are written into the same buffer";
  mesh_->setFlatTriangles(strip(10000), 0.0, green);  // 60,000 vertices: grows once
  EXPECT_EQ(mesh_->bufferAllocations(), 2u);
  EXPECT_GE(renderable().capacity(), 60000u);
  const std::vector<float> f = vertexFloats();
  EXPECT_FLOAT_EQ(f[(60000 - 2) * 4], 10000.0f) << "last triangle: x of its third-last vertex";
  mesh_->setFlatTriangles(strip(9000), 0.0, green);
  EXPECT_EQ(mesh_->bufferAllocations(), 2u);
}

TEST_F(FloorMeshTest, AHugePathsBufferIsGivenBackWhenPathsAreSmallAgain)
{
  const Ogre::ColourValue green(0, 1, 0, 1);
  mesh_->setFlatTriangles(strip(100000), 0.0, green);  // 600,000 vertices (14 MB)
  EXPECT_GE(renderable().capacity(), 600000u);
  mesh_->setFlatTriangles(strip(10), 0.0, green);
  EXPECT_LT(renderable().capacity(), 600000u / 8);
  EXPECT_EQ(vertexFloats().size(), 60u * 4);
}

TEST_F(FloorMeshTest, EmptyAndClearDrawNothing)
{
  mesh_->setFlatTriangles(strip(3), 0.0, Ogre::ColourValue::White);
  ASSERT_TRUE(renderable().isVisible());
  mesh_->setFlatTriangles({}, 0.0, Ogre::ColourValue::White);
  EXPECT_EQ(mesh_->triangleCount(), 0u);
  EXPECT_FALSE(renderable().isVisible());
  EXPECT_TRUE(vertexFloats().empty());
  mesh_->setFlatTriangles(strip(3), 0.0, Ogre::ColourValue::White);
  EXPECT_TRUE(renderable().isVisible());
  mesh_->clear();
  EXPECT_FALSE(renderable().isVisible());
  EXPECT_EQ(mesh_->triangleCount(), 0u);
}

TEST_F(FloorMeshTest, SolidTrianglesCarryNormalsAndSwitchingStyleChangesTheLayout)
{
  const std::vector<MeshVertex> solid{{{0, 0, 0.1}, {0, 0, 1}}, {{1, 0, 0.1}, {0, 0, 1}}, {{0, 1, 0.2}, {0, 0.6, 0.8}}};
  mesh_->setSolidTriangles(solid, 0.5, Ogre::ColourValue::Blue);
  std::vector<float> f = vertexFloats();
  ASSERT_EQ(f.size(), 3u * 6u);
  EXPECT_FLOAT_EQ(f[2], 0.6f);    // z + height
  EXPECT_FLOAT_EQ(f[5], 1.0f);    // normal z of vertex 0
  EXPECT_FLOAT_EQ(f[14], 0.7f);   // z of vertex 2
  EXPECT_FLOAT_EQ(f[16], 0.6f);   // normal y of vertex 2
  EXPECT_FLOAT_EQ(renderable().getBoundingBox().getMaximum().z, 0.7f);
  mesh_->setFlatTriangles(strip(1), 0.0, Ogre::ColourValue::Blue);
  EXPECT_EQ(vertexFloats().size(), 6u * 4u);
  EXPECT_EQ(mesh_->bufferAllocations(), 2u);
}
}  // namespace
