// One batched Ogre mesh of triangles for everything a display draws in one colour (all arrows in
// a single ManualObject, not a scene node per arrow).
#pragma once

#include <string>
#include <vector>

#include <OgreColourValue.h>
#include <OgreMaterial.h>

#include "rviz_projector/core/mesh_vertex.h"
#include "rviz_projector/core/vec2.h"

namespace Ogre
{
class ManualObject;
class SceneManager;
class SceneNode;
}  // namespace Ogre

namespace rviz_projector
{
class FloorMesh
{
public:
  FloorMesh(Ogre::SceneManager* scene_manager, Ogre::SceneNode* parent);
  ~FloorMesh();
  FloorMesh(const FloorMesh&) = delete;
  FloorMesh& operator=(const FloorMesh&) = delete;

  /// Flat, unlit triangles at height z: drawn in exactly `colour`.
  void setFlatTriangles(const std::vector<Vec2>& triangles, double z, const Ogre::ColourValue& colour);
  /// Shaded triangles (lit by the scene's lights), raised by z.
  void setSolidTriangles(const std::vector<MeshVertex>& triangles, double z, const Ogre::ColourValue& colour);
  void clear();

  /// Number of triangles currently drawn.
  std::size_t triangleCount() const { return triangle_count_; }
  Ogre::ManualObject* manualObject() const { return manual_; }

private:
  void setMaterial(bool lit, const Ogre::ColourValue& colour);
  void beginSection(std::size_t vertex_count, bool lit);

  Ogre::SceneManager* scene_manager_;
  Ogre::SceneNode* node_;
  Ogre::ManualObject* manual_;
  Ogre::MaterialPtr material_;
  std::size_t triangle_count_ = 0;
  bool section_lit_ = false;
  bool has_section_ = false;  // ManualObject section 0 exists (works on OGRE 1.9 and 1.12)
};
}  // namespace rviz_projector
