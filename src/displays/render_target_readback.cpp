#include "rviz_projector/displays/render_target_readback.h"

#include <OgrePixelFormat.h>
#include <OgrePrerequisites.h>
#include <OgreRenderTarget.h>

namespace rviz_projector
{
bool readRgbPixels(Ogre::RenderTarget* target, std::vector<std::uint8_t>& rgb, unsigned& width, unsigned& height)
{
  if (!target || target->getWidth() == 0 || target->getHeight() == 0)
  {
    return false;
  }
  width = target->getWidth();
  height = target->getHeight();
  rgb.resize(static_cast<std::size_t>(width) * height * 3);
  Ogre::PixelBox box(width, height, 1, Ogre::PF_BYTE_RGB, rgb.data());
#if OGRE_VERSION >= ((1 << 16) | (12 << 8))
  target->copyContentsToMemory(Ogre::Box(0, 0, width, height), box, Ogre::RenderTarget::FB_BACK);
#else
  target->copyContentsToMemory(box, Ogre::RenderTarget::FB_BACK);
#endif
  return true;
}
}  // namespace rviz_projector
