#include "rviz_projector/displays/projector_render_widget.h"

#include <algorithm>
#include <string>

#include <OgrePrerequisites.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <OgreStringConverter.h>
#include <QMoveEvent>
#include <QPaintEvent>
#include <QResizeEvent>
#include <QWindow>

#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
ProjectorRenderWidget::ProjectorRenderWidget(QWidget* parent, int fsaa) : QWidget(parent)
{
  setAttribute(Qt::WA_OpaquePaintEvent, true);
  setAttribute(Qt::WA_PaintOnScreen, true);
  const WId window_id = winId();  // creates the native window OGRE draws into
  const double pixel_ratio = windowHandle() ? windowHandle()->devicePixelRatio() : 1.0;

  // The parameters rviz uses for its own render windows, except multisampling. (rviz also sets
  // "externalGLControl" from a bool, which reads as false; true would make OGRE skip buffer swaps.)
  Ogre::NameValuePairList params;
  params["externalWindowHandle"] = Ogre::StringConverter::toString(static_cast<unsigned long>(window_id));
  params["parentWindowHandle"] = Ogre::StringConverter::toString(static_cast<unsigned long>(window_id));
  params["FSAA"] = Ogre::StringConverter::toString(fsaa);
  params["contentScalingFactor"] = std::to_string(pixel_ratio);
  render_window_ = Ogre::Root::getSingleton().createRenderWindow(
      uniqueOgreName("rviz_projector_window_"), static_cast<unsigned int>(std::max(1, width())),
      static_cast<unsigned int>(std::max(1, height())), false, &params);
  render_window_->setActive(true);
  render_window_->setAutoUpdated(false);  // rendered by the display's own timer
}

ProjectorRenderWidget::~ProjectorRenderWidget()
{
  if (render_window_)
  {
    render_window_->removeAllListeners();
    render_window_->removeAllViewports();
    Ogre::Root::getSingleton().destroyRenderTarget(render_window_);
    render_window_ = nullptr;
  }
}

void ProjectorRenderWidget::moveEvent(QMoveEvent* event)
{
  QWidget::moveEvent(event);
  if (render_window_)
  {
    render_window_->windowMovedOrResized();
  }
}

void ProjectorRenderWidget::paintEvent(QPaintEvent* event)
{
  if (repaint_request_)
  {
    repaint_request_();  // exposed again (e.g. un-minimised): the display renders its next frame
  }
  event->accept();
}

void ProjectorRenderWidget::resizeEvent(QResizeEvent* event)
{
  QWidget::resizeEvent(event);
  if (render_window_)
  {
    const double ratio = windowHandle() ? windowHandle()->devicePixelRatio() : 1.0;
    // Exact size, odd widths included: the image must map 1:1 onto the projector's pixels.
    render_window_->resize(static_cast<unsigned int>(width() * ratio), static_cast<unsigned int>(height() * ratio));
#if OGRE_VERSION < ((1 << 16) | (12 << 8))
    render_window_->windowMovedOrResized();  // OGRE 1.12 resizes its child window in resize()
#endif
  }
}
}  // namespace rviz_projector
