#include "rviz_projector/displays/warp_eraser.h"

#include <algorithm>

#include <OgreCamera.h>
#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgrePass.h>
#include <OgreRenderTexture.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneManagerEnumerator.h>
#include <OgreSceneNode.h>
#include <OgreTechnique.h>
#include <OgreViewport.h>

#include "rviz_projector/core/unorm8.h"
#include "rviz_projector/displays/image_space.h"
#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
std::array<std::uint8_t, 4> clearedBytes(float r, float g, float b, float a)
{
  return {unorm8(r), unorm8(g), unorm8(b), unorm8(a)};
}

WarpEraser::WarpEraser()
  : scene_(Ogre::Root::getSingleton().createSceneManager(Ogre::DefaultSceneManagerFactory::FACTORY_TYPE_NAME,
                                                         uniqueOgreName("rviz_projector_warp_eraser_scene_")))
  , camera_(scene_->createCamera(uniqueOgreName("rviz_projector_warp_eraser_camera_")))
  , mesh_(scene_->createManualObject(uniqueOgreName("rviz_projector_warp_eraser_")))
{
  // Image space, no depth test or write, no blending: the vertices' colour lands as it is.
  material_ = createImageSpaceMaterial("rviz_projector_warp_eraser_material_");
  useImageSpace(mesh_);
  mesh_->setDynamic(true);  // rewritten every frame
  mesh_->setVisible(false);
  scene_->getRootSceneNode()->attachObject(mesh_);
}

WarpEraser::~WarpEraser()
{
  attach(nullptr, 1, 1);
  scene_->getRootSceneNode()->detachAllObjects();
  scene_->destroyManualObject(mesh_);
  scene_->destroyCamera(camera_);
  Ogre::Root::getSingleton().destroySceneManager(scene_);
  Ogre::MaterialManager::getSingleton().remove(material_->getName(), material_->getGroup());
}

void WarpEraser::attach(Ogre::RenderTexture* target, std::uint32_t width, std::uint32_t height)
{
  if (target_ && viewport_)
  {
    target_->removeViewport(viewport_->getZOrder());
  }
  target_ = target;
  viewport_ = nullptr;
  width_ = std::max<std::uint32_t>(width, 1);
  height_ = std::max<std::uint32_t>(height, 1);
  mesh_->setVisible(false);
  written_rects_.clear();  // another size: the next paint() writes its quads anew
  if (target_)
  {
    viewport_ = target_->addViewport(camera_, -1);  // before the scene's (z-order 0)
    viewport_->setClearEveryFrame(false);
    viewport_->setOverlaysEnabled(false);
    viewport_->setSkiesEnabled(false);
    viewport_->setShadowsEnabled(false);
  }
}

void WarpEraser::paint(const std::vector<TexelRect>& rects, const std::array<std::uint8_t, 4>& rgba)
{
  mesh_->setVisible(!rects.empty() && viewport_ != nullptr);
  if (rects.empty() || viewport_ == nullptr || (rects == written_rects_ && rgba == written_rgba_))
  {
    return;  // nothing to paint, or the mesh holds these quads already (the same picture again)
  }
  written_rects_ = rects;
  written_rgba_ = rgba;
  if (written_)
  {
    mesh_->beginUpdate(0);
  }
  else
  {
    mesh_->begin(material_->getName(), Ogre::RenderOperation::OT_TRIANGLE_LIST,
                 Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
  }
  // OGRE packs a vertex colour as trunc(255 c): (byte + 0.5) / 255 packs to that byte exactly, and
  // OpenGL turns the byte back into byte / 255, which an 8-bit target stores as the byte.
  const Ogre::ColourValue colour((rgba[0] + 0.5f) / 255.0f, (rgba[1] + 0.5f) / 255.0f, (rgba[2] + 0.5f) / 255.0f,
                                 (rgba[3] + 0.5f) / 255.0f);
  const double w = width_, h = height_;
  Ogre::uint32 next = 0;
  for (const TexelRect& r : rects)
  {
    // Pixel edges -> normalised device coordinates (y up; the target's row 0 at the top).
    const auto left = static_cast<Ogre::Real>(2.0 * r.x0 / w - 1.0);
    const auto right = static_cast<Ogre::Real>(2.0 * r.x1 / w - 1.0);
    const auto top = static_cast<Ogre::Real>(1.0 - 2.0 * r.y0 / h);
    const auto bottom = static_cast<Ogre::Real>(1.0 - 2.0 * r.y1 / h);
    for (const auto& corner : {std::make_pair(left, top), std::make_pair(right, top), std::make_pair(left, bottom),
                               std::make_pair(right, bottom)})
    {
      mesh_->position(corner.first, corner.second, 0.0f);
      mesh_->colour(colour);
    }
    mesh_->triangle(next, next + 2, next + 1);
    mesh_->triangle(next + 1, next + 2, next + 3);
    next += 4;
  }
  mesh_->end();
  if (!written_)
  {
    mesh_->setBoundingBox(Ogre::AxisAlignedBox::BOX_INFINITE);  // in image space: never culled
  }
  written_ = true;
}
}  // namespace rviz_projector
