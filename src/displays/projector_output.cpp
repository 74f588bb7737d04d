#include "rviz_projector/displays/projector_output.h"

#include <algorithm>
#include <set>

#include <OgreCamera.h>
#include <OgreException.h>
#include <OgreRenderWindow.h>
#include <OgreViewport.h>
#include <QCoreApplication>
#include <QGuiApplication>
#include <QScreen>
#include <QWidget>
#include <QWindow>

#include "rviz_projector/core/screen_choice.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_projector/displays/viewport_clear.h"

namespace rviz_projector
{
namespace
{
/// Every ProjectorOutput of the process (main thread only): two projectors on "Automatic" must
/// not stack on one screen.
std::set<const ProjectorOutput*>& allOutputs()
{
  static std::set<const ProjectorOutput*> outputs;
  return outputs;
}

QString describe(const QScreen* screen)
{
  const QRect g = screen->geometry();
  return QString("%1 (%2x%3 at %4,%5)").arg(screen->name()).arg(g.width()).arg(g.height()).arg(g.x()).arg(g.y());
}

/// A normal window for an image of `image` pixels: shrunk to fit the screen (to half of it in
/// rviz's corner when it shares rviz's screen), centred.
QRect defaultWindowedGeometry(const QScreen* screen, const QSize& image, bool corner)
{
  const QRect available = screen->availableGeometry();
  QSize size = image;
  size.scale(size.boundedTo(available.size() * (corner ? 0.5 : 0.8)), Qt::KeepAspectRatio);
  const QPoint origin = corner ? available.bottomRight() - QPoint(size.width() - 1, size.height() - 1) :
                                 available.center() - QPoint(size.width() / 2, size.height() / 2);
  return QRect(origin, size);
}
}  // namespace

ProjectorOutput::ProjectorOutput(const QString& title, Ogre::Camera* camera, Ogre::RenderTargetListener* listener,
                                 const RenderPolicy& policy)
  : title_(title), camera_(camera), listener_(listener), policy_(policy)
{
  allOutputs().insert(this);
  if (QCoreApplication::instance() != nullptr)
  {
    connect(QCoreApplication::instance(), &QCoreApplication::aboutToQuit, this, &ProjectorOutput::onApplicationQuit);
  }
}

ProjectorOutput::~ProjectorOutput()
{
  allOutputs().erase(this);
  destroy();
}

std::vector<std::string> ProjectorOutput::screensInUse(const ProjectorOutput* except)
{
  std::vector<std::string> names;
  for (const ProjectorOutput* output : allOutputs())
  {
    if (output != except && output->isShown() && !output->screen_name_.empty())
    {
      names.push_back(output->screen_name_);
    }
  }
  return names;
}

QScreen* ProjectorOutput::screenOf(const QWidget* widget)
{
  const QWidget* top = widget ? widget->window() : nullptr;
  return top && top->windowHandle() ? top->windowHandle()->screen() : nullptr;
}

std::string ProjectorOutput::screenName(const QString& value)
{
  const int cut = value.indexOf(" (");
  return (cut < 0 ? value : value.left(cut)).trimmed().toStdString();
}

bool ProjectorOutput::screenConnected(const std::string& name)
{
  const QList<QScreen*> screens = QGuiApplication::screens();
  return std::any_of(screens.begin(), screens.end(),
                     [&name](const QScreen* s) { return s->name().toStdString() == name; });
}

QString ProjectorOutput::scalingNote(std::uint32_t image_width, std::uint32_t image_height) const
{
  if (image_rect_.width == static_cast<int>(image_width) && image_rect_.height == static_cast<int>(image_height))
  {
    return QString();
  }
  return QString("Window %1x%2 differs from the %3x%4 image: scaled to %5x%6, letterboxed (not 1:1)")
      .arg(window_width_)
      .arg(window_height_)
      .arg(image_width)
      .arg(image_height)
      .arg(image_rect_.width)
      .arg(image_rect_.height);
}

bool ProjectorOutput::isShown() const
{
  return window_ && window_->isVisible();
}

void ProjectorOutput::setTitle(const QString& title)
{
  if (title == title_)
  {
    return;
  }
  title_ = title;
  if (window_)
  {
    window_->setWindowTitle(title_);
  }
}

double ProjectorOutput::refreshRate() const
{
  const QWindow* handle = window_ ? window_->windowHandle() : nullptr;
  return handle && handle->screen() ? handle->screen()->refreshRate() : 0.0;
}

Ogre::RenderWindow* ProjectorOutput::renderWindow() const
{
  return window_ ? window_->renderWindow() : nullptr;
}

bool ProjectorOutput::create(bool full_screen, int fsaa, QString& error)
{
  try
  {
    window_ = std::make_unique<ProjectorOutputWindow>(title_, full_screen, fsaa);
    Ogre::RenderWindow* render_window = window_->renderWindow();
    render_window->addListener(listener_);
    viewport_ = render_window->addViewport(camera_);
  }
  catch (const std::exception& e)  // Ogre::Exception, std::bad_alloc: GL errors, exhausted resources
  {
    error = QString::fromLocal8Bit(e.what());
    destroy();
    return false;
  }
  viewport_->setOverlaysEnabled(false);
  viewport_->setShadowsEnabled(false);
  viewport_->setSkiesEnabled(false);
  setClearedBuffers(*viewport_, kProjectorClearBuffers);
  viewport_->setBackgroundColour(background_);
  viewport_->setVisibilityMask(visibility_mask_);
  image_rect_ = PixelRect();
  window_width_ = window_height_ = 0;
  window_->setRepaintRequest([this] { repaint_requested_ = true; });
  // Esc and the close button arrive inside the window's own event handlers: act after they return.
  connect(window_.get(), &ProjectorOutputWindow::leaveFullScreenRequested, this,
          &ProjectorOutput::leaveFullScreenRequested, Qt::QueuedConnection);
  connect(window_.get(), &ProjectorOutputWindow::closedByUser, this, &ProjectorOutput::closedByUser,
          Qt::QueuedConnection);
  return true;
}

void ProjectorOutput::destroy()
{
  if (!window_)
  {
    return;
  }
  rememberUserGeometry();
  window_->disconnect(this);
  // Order matters: listener, viewport, render window (in the widget's destructor), widget.
  if (Ogre::RenderWindow* render_window = window_->renderWindow())
  {
    render_window->removeListener(listener_);
    render_window->removeAllViewports();
  }
  viewport_ = nullptr;
  screen_name_.clear();
  window_.reset();
}

void ProjectorOutput::rememberUserGeometry()
{
  // Only a geometry the user gave the window (moved or resized it), not one placed here.
  if (window_ && !window_->isFullScreenOn() && window_->isVisible() && window_->geometry() != placed_geometry_)
  {
    windowed_geometry_ = window_->geometry();
  }
}

void ProjectorOutput::hide()
{
  if (window_)
  {
    rememberUserGeometry();
    window_->hide();
  }
  screen_name_.clear();
}

void ProjectorOutput::onApplicationQuit()
{
  hide();  // the floor goes dark as rviz quits
}

OutputResult ProjectorOutput::present(const OutputRequest& request)
{
  OutputResult result;
  const QList<QScreen*> qt_screens = QGuiApplication::screens();
  std::vector<ScreenInfo> screens;
  int rviz_index = -1;
  const QList<QScreen*> siblings = request.rviz_screen ? request.rviz_screen->virtualSiblings() : QList<QScreen*>();
  for (int i = 0; i < qt_screens.size(); ++i)
  {
    QScreen* s = qt_screens[i];
    ScreenInfo info;
    info.name = s->name().toStdString();
    const QRect g = s->geometry();
    info.x = g.x();
    info.y = g.y();
    info.width = g.width();
    info.height = g.height();
    info.same_x_screen = request.rviz_screen == nullptr || siblings.contains(s);
    screens.push_back(info);
    if (s == request.rviz_screen)
    {
      rviz_index = i;
    }
  }
  const ScreenChoice choice = chooseScreen(screens, rviz_index, request.screen, screensInUse(this));
  const QString problem = QString::fromStdString(choice.problem);
  if (choice.index < 0)
  {
    hide();
    result.level = OutputResult::Warn;
    result.text = problem + ": output window hidden until a screen appears";
    return result;
  }
  QScreen* screen = qt_screens[choice.index];
  // Never full screen over rviz by accident: when Automatic ends up on rviz's own screen, or only
  // one screen exists, the window opens windowed. A screen the user named explicitly is obeyed.
  const bool named = request.screen != kAutomaticScreen && !request.screen.empty() && problem.isEmpty();
  // projector_host has no rviz window to cover: full screen on the only screen, when the robot has
  // only the projector. Once several screens were seen, the primary is kept free as in rviz (a
  // projector unplugged from a robot with a monitor: windowed on the monitor until it is back).
  seen_several_screens_ = seen_several_screens_ || qt_screens.size() >= 2;
  const bool shares_rviz = policy_.host ? (seen_several_screens_ && choice.shares_rviz_screen && !named) :
                                        (qt_screens.size() < 2 || (choice.shares_rviz_screen && !named));
  const bool full_screen = request.full_screen && !shares_rviz;
  if (!window_ || window_->isFullScreenOn() != full_screen || window_->fsaa() != request.fsaa)
  {
    // Frameless or framed, and the multisampling, are fixed per native window: a new one.
    destroy();
    QString error;
    if (!create(full_screen, request.fsaa, error))
    {
      result.level = OutputResult::Error;
      result.text = "Cannot create the output window (" + error + "): the projector shows nothing";
      return result;
    }
  }
  const QSize image = request.image_width > 0 && request.image_height > 0 ?
                          QSize(static_cast<int>(request.image_width), static_cast<int>(request.image_height)) :
                          QSize(1280, 800);
  const bool same_screen =
      window_->isVisible() && screen_name_ == screens[static_cast<std::size_t>(choice.index)].name;
  if (full_screen)
  {
    window_->showFullScreenOn(screen);
  }
  else
  {
    rememberUserGeometry();
    // The user's own geometry wins while it is on this screen; otherwise a default placement for
    // the image size (again when the image size changes, as long as the user kept it).
    const QRect geometry = windowed_geometry_.isValid() && screen->geometry().intersects(windowed_geometry_) ?
                               windowed_geometry_ :
                               defaultWindowedGeometry(screen, image, shares_rviz);
    if (!same_screen || window_->geometry() != geometry)
    {
      window_->showWindowedOn(screen, geometry);
      placed_geometry_ = geometry;
    }
  }
  screen_name_ = screens[static_cast<std::size_t>(choice.index)].name;
  result.shown = true;
  const QString text = QString("%1 on %2").arg(full_screen ? "Full screen" : "Window").arg(describe(screen));
  if (shares_rviz)
  {
    result.level = OutputResult::Warn;
    result.text = (problem.isEmpty() ? QString() : problem + "; ") + "only rviz's screen is available: " + text +
                  ", in a corner so as not to cover rviz (connect the projector as an extended desktop)";
  }
  else
  {
    result.level = problem.isEmpty() ? OutputResult::Ok : OutputResult::Warn;
    result.text = problem.isEmpty() ? text : problem + "; using " + text;
  }
  if (!window_->setupProblem().isEmpty())
  {
    result.level = OutputResult::Error;
    result.text = text + ", but " + window_->setupProblem();
  }
  return result;
}

bool ProjectorOutput::fitViewport(std::uint32_t image_width, std::uint32_t image_height)
{
  Ogre::RenderWindow* rw = renderWindow();
  if (!rw || !viewport_)
  {
    return false;
  }
  const int ww = static_cast<int>(rw->getWidth());
  const int wh = static_cast<int>(rw->getHeight());
  const PixelRect rect = letterbox(image_width, image_height, ww, wh);
  if (rect == image_rect_ && ww == window_width_ && wh == window_height_)
  {
    return false;
  }
  image_rect_ = rect;
  window_width_ = ww;
  window_height_ = wh;
  if (ww > 0 && wh > 0)
  {
    const auto f = viewportFractions(rect, ww, wh);
    viewport_->setDimensions(f[0], f[1], f[2], f[3]);
  }
  return true;
}

void ProjectorOutput::setBackground(const Ogre::ColourValue& colour)
{
  background_ = colour;
  if (viewport_)
  {
    viewport_->setBackgroundColour(colour);
  }
}

void ProjectorOutput::setVisibilityMask(std::uint32_t mask)
{
  visibility_mask_ = mask;
  if (viewport_ && viewport_->getVisibilityMask() != mask)
  {
    viewport_->setVisibilityMask(mask);
  }
}

void ProjectorOutput::render(bool swap_buffers)
{
  Ogre::RenderWindow* rw = renderWindow();
  if (!rw)
  {
    return;
  }
  rw->update(false);
  if (swap_buffers)
  {
    rw->swapBuffers();
  }
}

void ProjectorOutput::swap()
{
  if (Ogre::RenderWindow* rw = renderWindow())
  {
    rw->swapBuffers();
  }
}
}  // namespace rviz_projector
