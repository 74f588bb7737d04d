// The vertex buffer behind FloorMesh: one triangle list in a dynamic hardware vertex buffer that
// is written in place through a pointer (no per-vertex calls, no staging copy) and reallocated
// only when it must grow (or is far too large), so a new path costs one lock, a linear write and
// one unlock.
#pragma once

#include <cstddef>

#include <OgreAxisAlignedBox.h>
#include <OgreHardwareVertexBuffer.h>
#include <OgreSimpleRenderable.h>

namespace rviz_projector
{
class FloorMeshRenderable : public Ogre::SimpleRenderable
{
public:
  /// Vertex layout: position (3 floats) and then a packed colour (4 bytes) or a normal (3 floats).
  enum class Layout
  {
    PositionColour,
    PositionNormal
  };

  FloorMeshRenderable();
  ~FloorMeshRenderable() override;
  FloorMeshRenderable(const FloorMeshRenderable&) = delete;
  FloorMeshRenderable& operator=(const FloorMeshRenderable&) = delete;

  /// Locks room for `vertex_count` vertices of `layout` for writing; the previous contents are
  /// discarded. Write floatsPerVertex(layout) floats per vertex, then call unlock().
  float* lock(std::size_t vertex_count, Layout layout);
  /// Draws the `vertex_count` vertices just written; `bounds` is their bounding box.
  void unlock(std::size_t vertex_count, const Ogre::AxisAlignedBox& bounds);
  /// Draws nothing (keeps the buffer for the next lock).
  void clear();

  static std::size_t floatsPerVertex(Layout layout) { return layout == Layout::PositionColour ? 4 : 6; }
  /// Vertices the current buffer holds (0 before the first lock).
  std::size_t capacity() const { return capacity_; }
  /// How often the hardware buffer was (re)allocated: stays put while paths fit.
  std::size_t allocations() const { return allocations_; }

  Ogre::Real getSquaredViewDepth(const Ogre::Camera* camera) const override;
  Ogre::Real getBoundingRadius() const override;

private:
  void allocate(std::size_t capacity, Layout layout);

  Ogre::HardwareVertexBufferSharedPtr buffer_;
  std::size_t capacity_ = 0;
  std::size_t allocations_ = 0;
  Layout layout_ = Layout::PositionColour;
  Ogre::Real radius_ = 0;
};
}  // namespace rviz_projector
