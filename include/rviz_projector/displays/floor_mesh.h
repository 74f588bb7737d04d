// One batched Ogre mesh of triangles for everything a display draws in one colour (all arrows in
// one vertex buffer and one draw call, not a scene node per arrow). A new set of triangles is
// written straight into the reused hardware buffer (FloorMeshRenderable).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <OgreColourValue.h>
#include <OgreMaterial.h>

#include "rviz_projector/core/mesh_vertex.h"
#include "rviz_projector/core/vec2.h"

namespace Ogre
{
class SceneManager;
class SceneNode;
}  // namespace Ogre

namespace rviz_projector
{
class FloorMeshRenderable;

class FloorMesh
{
public:
  FloorMesh(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent);
  ~FloorMesh();
  FloorMesh(const FloorMesh&) = delete;
  FloorMesh& operator=(const FloorMesh&) = delete;

  /// Flat, unlit triangles at height z: drawn in exactly `colour`.
  void setFlatTriangles(const std::vector<Vec2>& triangles, double z, const Ogre::ColourValue& colour);
  /// The same, each vertex's opacity multiplied by its factor in `alpha` (one per vertex, 0..1;
  /// missing factors count as 1): the horizon's fading arrows.
  void setFlatTriangles(const std::vector<Vec2>& triangles, const std::vector<float>& alpha, double z,
                        const Ogre::ColourValue& colour);
  /// Shaded triangles (lit by the scene's lights), raised by z.
  void setSolidTriangles(const std::vector<MeshVertex>& triangles, double z, const Ogre::ColourValue& colour);
  void clear();
  /// Shown or hidden whatever its content (a display's own switch; a new upload keeps it). A
  /// scene node's setVisible() is not enough: each upload makes a non-empty mesh visible again.
  void setShown(bool shown);
  /// OGRE visibility flags of the mesh (which viewports show it); rviz sets them for displays' nodes.
  void setVisibilityFlags(std::uint32_t flags);
  /// Where the mesh lies in a stack of floor layers drawn at (almost) the same height: layers are
  /// drawn in increasing order, so a higher layer always covers a lower one where they overlap
  /// (the arrows over the stop zone's bar). Without it OGRE sorts translucent meshes by their
  /// distance from the camera, which changes with their shapes: the order would flip from frame
  /// to frame. Opaque geometry of layer 0 (the default: the mask's occluders) is drawn first.
  void setLayer(std::uint16_t layer);

  /// Number of triangles currently drawn.
  std::size_t triangleCount() const { return triangle_count_; }
  /// How often the vertex buffer was (re)allocated; paths that fit in it do not allocate.
  std::size_t bufferAllocations() const;

private:
  void setMaterial(bool lit, const Ogre::ColourValue& colour);

  Ogre::SceneManager* scene_manager_;
  Ogre::SceneNode* node_;
  std::unique_ptr<FloorMeshRenderable> renderable_;
  Ogre::MaterialPtr material_;
  std::size_t triangle_count_ = 0;
  bool shown_ = true;
};
}  // namespace rviz_projector
