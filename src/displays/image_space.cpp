#include "rviz_projector/displays/image_space.h"

#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgrePass.h>
#include <OgreResourceGroupManager.h>
#include <OgreTechnique.h>

#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
Ogre::MaterialPtr createImageSpaceMaterial(const char* prefix)
{
  Ogre::MaterialPtr material = Ogre::MaterialManager::getSingleton().create(
      uniqueOgreName(prefix), Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
  Ogre::Pass* pass = material->getTechnique(0)->getPass(0);
  pass->setLightingEnabled(false);
  pass->setDepthCheckEnabled(false);
  pass->setDepthWriteEnabled(false);
  pass->setCullingMode(Ogre::CULL_NONE);
  material->setReceiveShadows(false);
  return material;
}

void useImageSpace(Ogre::ManualObject* object)
{
  object->setUseIdentityProjection(true);
  object->setUseIdentityView(true);
  object->setDynamic(false);
}
}  // namespace rviz_projector
