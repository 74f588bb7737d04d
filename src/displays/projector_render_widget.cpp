#include "rviz_projector/displays/projector_render_widget.h"

#include <OgreRenderWindow.h>
#include <OgreRoot.h>

#include <rviz/ogre_helpers/render_system.h>

namespace rviz_projector
{
ProjectorRenderWidget::ProjectorRenderWidget(QWidget* parent)
  : rviz::RenderWidget(rviz::RenderSystem::get(), parent)
{
}

ProjectorRenderWidget::~ProjectorRenderWidget()
{
  if (render_window_)
  {
    render_window_->removeAllListeners();
    render_window_->removeAllViewports();
    Ogre::Root::getSingleton().destroyRenderTarget(render_window_);
    render_window_ = nullptr;  // the base destructor then has nothing left to tear down
  }
}
}  // namespace rviz_projector
