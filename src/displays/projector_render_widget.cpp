#include "rviz_projector/displays/projector_render_widget.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <vector>

#include <OgrePrerequisites.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <OgreStringConverter.h>
#include <QMoveEvent>
#include <QPaintEvent>
#include <QResizeEvent>
#include <QWindow>
#include <ros/console.h>

#include "rviz_projector/displays/ogre_name.h"
#include "rviz_projector/displays/x_error_watch.h"

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
  // OGRE creates its window on one X connection, the GL driver first uses it on another: if the X
  // server refuses the driver's requests (it took them before the window's creation, on a loaded
  // machine), no frame would ever reach the window. Created again then (x_error_watch.h).
  int refuse = testRefusals();
  for (int attempt = 1;; ++attempt)
  {
    XErrorWatch watch;
    render_window_ = Ogre::Root::getSingleton().createRenderWindow(
        uniqueOgreName("rviz_projector_window_"), static_cast<unsigned int>(std::max(1, width())),
        static_cast<unsigned int>(std::max(1, height())), false, &params);
    for (const char* connection : {"XDISPLAY", "DISPLAY"})
    {
      void* display = nullptr;
      render_window_->getCustomAttribute(connection, &display);
      watch.sync(display);
    }
    std::vector<std::string> errors = watch.errors();
    if (refuse > 0)
    {
      --refuse;
      errors.emplace_back("refused for the test (RVIZ_PROJECTOR_TEST_REFUSE_WINDOWS)");
    }
    if (errors.empty())
    {
      if (attempt > 1)
      {
        ROS_INFO("rviz_projector: the projector's render window works on attempt %d", attempt);
      }
      break;
    }
    std::string all;
    for (const std::string& e : errors)
    {
      all += (all.empty() ? "" : "; ") + e;
    }
    if (attempt == kCreateAttempts)
    {
      setup_problem_ = "the X server refused the GL driver's use of the projector's window " +
                       std::to_string(attempt) + " times (" + all + "): its frames may not reach the screen";
      ROS_ERROR("rviz_projector: %s", setup_problem_.c_str());
      break;
    }
    ROS_WARN("rviz_projector: the X server refused the GL driver's first use of the projector's new render "
             "window (%s): creating it again (attempt %d of %d)",
             all.c_str(), attempt + 1, kCreateAttempts);
    destroyRenderWindow();
  }
  render_window_->setActive(true);
  render_window_->setAutoUpdated(false);  // rendered by the display's own timer
}

int ProjectorRenderWidget::testRefusals()
{
  const char* value = std::getenv("RVIZ_PROJECTOR_TEST_REFUSE_WINDOWS");
  return value == nullptr ? 0 : std::max(0, std::atoi(value));
}

void ProjectorRenderWidget::destroyRenderWindow()
{
  if (render_window_)
  {
    render_window_->removeAllListeners();
    render_window_->removeAllViewports();
    Ogre::Root::getSingleton().destroyRenderTarget(render_window_);
    render_window_ = nullptr;
  }
}

ProjectorRenderWidget::~ProjectorRenderWidget()
{
  destroyRenderWindow();
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
