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
  // rviz's main window is the application: closing it must quit even while this one is shown.
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

Ogre::RenderWindow* ProjectorOutputWindow::renderWindow() const
{
  return render_widget_->renderWindow();
}

void ProjectorOutputWindow::present(QScreen* screen, const QSize& image_size, bool corner)
{
  if (!windowHandle())
  {
    create();
  }
  // Qt needs the native window on the target screen before it goes full screen there.
  if (screen && windowHandle() && windowHandle()->screen() != screen)
  {
    if (isFullScreen())
    {
      showNormal();
    }
    windowHandle()->setScreen(screen);
  }
  if (full_screen_ && screen)
  {
    setCursor(Qt::BlankCursor);
    setGeometry(screen->geometry());
    showFullScreen();
  }
  else
  {
    unsetCursor();
    QSize size = image_size.isValid() ? image_size : QSize(1280, 800);
    if (screen)
    {
      const QRect available = screen->availableGeometry();
      size.scale(size.boundedTo(available.size() * (corner ? 0.5 : 0.8)), Qt::KeepAspectRatio);
      const QPoint origin = corner ? available.bottomRight() - QPoint(size.width() - 1, size.height() - 1)
                                   : available.center() - QPoint(size.width() / 2, size.height() / 2);
      setGeometry(QRect(origin, size));
    }
    else
    {
      resize(size);
    }
    showNormal();
  }
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
