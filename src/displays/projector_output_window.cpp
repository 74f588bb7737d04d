#include "rviz_projector/displays/projector_output_window.h"

#include <QCloseEvent>
#include <QKeyEvent>
#include <QScreen>
#include <QVBoxLayout>
#include <QWindow>

#include "rviz_projector/displays/projector_render_widget.h"

namespace rviz_projector
{
ProjectorOutputWindow::ProjectorOutputWindow(const QString& title, bool full_screen, int fsaa)
  : QWidget(nullptr, full_screen ? Qt::Window | Qt::FramelessWindowHint : Qt::Window)
  , full_screen_(full_screen)
  , fsaa_(fsaa)
{
  setWindowTitle(title);
  setAttribute(Qt::WA_DeleteOnClose, false);
  // Not a window that keeps rviz alive: when rviz's main window closes (Ctrl+Q, File -> Quit, its
  // close button, SIGINT/SIGTERM through rviz's own shutdown), the application must quit.
  setAttribute(Qt::WA_QuitOnClose, false);
  QPalette black = palette();
  black.setColor(QPalette::Window, Qt::black);
  setPalette(black);
  setAutoFillBackground(true);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  render_widget_ = new ProjectorRenderWidget(this, fsaa);
  layout->addWidget(render_widget_);
}

ProjectorOutputWindow::~ProjectorOutputWindow() = default;

void ProjectorOutputWindow::setRepaintRequest(std::function<void()> request)
{
  render_widget_->setRepaintRequest(std::move(request));
}

Ogre::RenderWindow* ProjectorOutputWindow::renderWindow() const
{
  return render_widget_->renderWindow();
}

QString ProjectorOutputWindow::setupProblem() const
{
  return QString::fromStdString(render_widget_->setupProblem());
}

QSize ProjectorOutputWindow::drawingPixels() const
{
  const double ratio = render_widget_->windowHandle() ? render_widget_->windowHandle()->devicePixelRatio() : 1.0;
  return QSize(static_cast<int>(render_widget_->width() * ratio), static_cast<int>(render_widget_->height() * ratio));
}

void ProjectorOutputWindow::moveToScreen(QScreen* screen)
{
  if (!windowHandle())
  {
    create();
  }
  if (screen && windowHandle() && windowHandle()->screen() != screen)
  {
    if (isFullScreen())
    {
      showNormal();
    }
    windowHandle()->setScreen(screen);
  }
}

void ProjectorOutputWindow::showFullScreenOn(QScreen* screen)
{
  moveToScreen(screen);
  setCursor(Qt::BlankCursor);
  if (screen)
  {
    setGeometry(screen->geometry());
  }
  showFullScreen();
  raise();
}

void ProjectorOutputWindow::showWindowedOn(QScreen* screen, const QRect& geometry)
{
  moveToScreen(screen);
  unsetCursor();
  setGeometry(geometry);
  showNormal();
  raise();
}

void ProjectorOutputWindow::keyPressEvent(QKeyEvent* event)
{
  if (event->key() == Qt::Key_Escape && full_screen_)
  {
    Q_EMIT leaveFullScreenRequested();
    event->accept();
    return;
  }
  QWidget::keyPressEvent(event);
}

void ProjectorOutputWindow::closeEvent(QCloseEvent* event)
{
  // Closing hides the window; the display decides what that means (it disables itself).
  event->ignore();
  hide();
  Q_EMIT closedByUser();
}
}  // namespace rviz_projector
