#include "rviz_projector/displays/projector_crosshairs.h"

#include <OgreCamera.h>
#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgrePass.h>
#include <OgreResourceGroupManager.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneManagerEnumerator.h>
#include <OgreSceneNode.h>
#include <OgreTechnique.h>

#include "rviz_projector/displays/image_space.h"
#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
std::array<double, 4> ndcOfPatternRect(const PatternRect& rect, std::uint32_t width, std::uint32_t height)
{
  const double w = static_cast<double>(width);
  const double h = static_cast<double>(height);
  // Window x = pixel x + 0.5; NDC x = 2 * window x / W - 1. Window y runs up from the bottom edge:
  // NDC y = 1 - 2 * (pixel y + 0.5) / H.
  return {2.0 * (rect.x0 + 0.5) / w - 1.0, 1.0 - 2.0 * (rect.y1 + 0.5) / h, 2.0 * (rect.x1 + 0.5) / w - 1.0,
          1.0 - 2.0 * (rect.y0 + 0.5) / h};
}

ProjectorCrosshairs::ProjectorCrosshairs()
  : scene_manager_(Ogre::Root::getSingleton().createSceneManager(
        Ogre::DefaultSceneManagerFactory::FACTORY_TYPE_NAME, uniqueOgreName("rviz_projector_crosshairs_scene_")))
  , camera_(scene_manager_->createCamera(uniqueOgreName("rviz_projector_crosshairs_camera_")))
  , quads_object_(scene_manager_->createManualObject(uniqueOgreName("rviz_projector_crosshairs_")))
{
  material_ = createImageSpaceMaterial("rviz_projector_crosshairs_material_");
  material_->getTechnique(0)->getPass(0)->setVertexColourTracking(Ogre::TVC_DIFFUSE);
  useImageSpace(quads_object_);
  scene_manager_->getRootSceneNode()->attachObject(quads_object_);
}

ProjectorCrosshairs::~ProjectorCrosshairs()
{
  scene_manager_->getRootSceneNode()->detachAllObjects();
  scene_manager_->destroyManualObject(quads_object_);
  scene_manager_->destroyCamera(camera_);
  Ogre::Root::getSingleton().destroySceneManager(scene_manager_);
  Ogre::MaterialManager::getSingleton().remove(material_->getName(), material_->getGroup());
}

bool ProjectorCrosshairs::update(std::uint32_t width, std::uint32_t height, int rows, int cols, std::string& problem)
{
  problem = crosshairPatternProblem(width, height, rows, cols);
  const std::array<long long, 4> key{width, height, rows, cols};
  if (key == key_)
  {
    return false;
  }
  key_ = key;
  pattern_ = problem.empty() ? crosshairPattern(width, height, rows, cols) : std::vector<Crosshair>();
  const std::vector<PatternRect> rects = crosshairPatternRects(pattern_, width, height);
  quads_object_->clear();
  quads_ = 0;
  if (!rects.empty())
  {
    quads_object_->estimateVertexCount(4 * rects.size());
    quads_object_->estimateIndexCount(6 * rects.size());
    quads_object_->begin(material_->getName(), Ogre::RenderOperation::OT_TRIANGLE_LIST,
                         Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
    for (const PatternRect& rect : rects)
    {
      const std::array<double, 4> ndc = ndcOfPatternRect(rect, width, height);
      const auto corner = [&](double x, double y) {
        quads_object_->position(static_cast<Ogre::Real>(x), static_cast<Ogre::Real>(y), 0.0f);
        quads_object_->colour(Ogre::ColourValue::White);
      };
      corner(ndc[0], ndc[1]);
      corner(ndc[2], ndc[1]);
      corner(ndc[2], ndc[3]);
      corner(ndc[0], ndc[3]);
      const auto base = static_cast<Ogre::uint32>(4 * quads_);
      quads_object_->quad(base, base + 1, base + 2, base + 3);
      ++quads_;
    }
    quads_object_->end();
    // In image space: never culled by the (unused) camera's frustum.
    quads_object_->setBoundingBox(Ogre::AxisAlignedBox::BOX_INFINITE);
  }
  return true;
}
}  // namespace rviz_projector
