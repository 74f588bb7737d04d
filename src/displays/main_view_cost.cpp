#include "rviz_projector/displays/main_view_cost.h"

#include <OgreRenderSystem.h>
#include <OgreRenderSystemCapabilities.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <rviz/display_context.h>
#include <rviz/render_panel.h>
#include <rviz/view_manager.h>

#include "rviz_projector/core/ascii_lower.h"

namespace rviz_projector
{
bool isSoftwareRenderer(const std::string& gl_renderer)
{
  const std::string name = asciiLower(gl_renderer);
  for (const char* software : {"llvmpipe", "softpipe", "software rasterizer", "swr", "gdi generic"})
  {
    if (name.find(software) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

std::string mainViewCostWarning(unsigned int fsaa, const std::string& gl_renderer)
{
  if (fsaa <= 1 || !isSoftwareRenderer(gl_renderer))
  {
    return std::string();
  }
  return "rviz's main view renders with " + std::to_string(fsaa) + "x anti-aliasing on a software renderer (" +
         gl_renderer +
         "): that alone keeps about a core busy and holds the projector window below its frame rate. Start rviz "
         "with --disable-anti-aliasing (demo.launch does), or lower Global Options > Frame Rate.";
}

std::string mainViewCostWarning(rviz::DisplayContext& context, const RenderPolicy& policy)
{
  if (policy.host)
  {
    return std::string();  // projector_host renders no main view
  }
  // The main view's render window and the renderer are fixed for the life of rviz.
  rviz::ViewManager* views = context.getViewManager();
  rviz::RenderPanel* panel = views != nullptr ? views->getRenderPanel() : nullptr;
  Ogre::RenderWindow* main_window = panel != nullptr ? panel->getRenderWindow() : nullptr;
  Ogre::RenderSystem* render_system = Ogre::Root::getSingleton().getRenderSystem();
  const Ogre::RenderSystemCapabilities* capabilities =
      render_system != nullptr ? render_system->getCapabilities() : nullptr;
  return main_window != nullptr && capabilities != nullptr ?
             mainViewCostWarning(main_window->getFSAA(), capabilities->getDeviceName()) :
             std::string();
}
}  // namespace rviz_projector
