// The projector's output: a frameless top-level window holding an OGRE render window, full screen
// on the projector's screen. Owned by ProjectorCameraDisplay; never a dock panel of rviz (rviz
// disables a display whose panel gets hidden, e.g. when its main window is minimised).
#pragma once

#include <functional>

#include <QWidget>

namespace Ogre
{
class RenderWindow;
}
class QScreen;

namespace rviz_projector
{
class ProjectorRenderWidget;

class ProjectorOutputWindow : public QWidget
{
  Q_OBJECT
public:
  /// Full screen windows are frameless; a windowed one has a normal frame so it can be resized.
  /// The choice is made at construction (changing flags later would recreate the native window
  /// under the OGRE render window), so the display builds a new window when it toggles.
  /// `fsaa`: multisampling samples of the render window (0 = off).
  ProjectorOutputWindow(const QString& title, bool full_screen, int fsaa);
  ~ProjectorOutputWindow() override;

  Ogre::RenderWindow* renderWindow() const;
  /// Empty, or why frames may not reach the window (ProjectorRenderWidget::setupProblem).
  QString setupProblem() const;
  /// The render widget's size in device pixels (what OGRE's render window should be).
  QSize drawingPixels() const;
  /// See ProjectorRenderWidget::setRepaintRequest.
  void setRepaintRequest(std::function<void()> request);

  /// Full screen on `screen` (cursor hidden); moves there first (Qt needs the native window on
  /// the target screen before it goes full screen there).
  void showFullScreenOn(QScreen* screen);
  /// A normal window on `screen` with this geometry.
  void showWindowedOn(QScreen* screen, const QRect& geometry);
  bool isFullScreenOn() const { return full_screen_; }
  int fsaa() const { return fsaa_; }

Q_SIGNALS:
  /// The user pressed Esc in full screen (connect queued: the window may be rebuilt).
  void leaveFullScreenRequested();
  /// The user closed the window (window manager close button, Alt+F4).
  void closedByUser();

protected:
  void keyPressEvent(QKeyEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

private:
  void moveToScreen(QScreen* screen);

  ProjectorRenderWidget* render_widget_;
  bool full_screen_ = false;
  int fsaa_ = 0;
};
}  // namespace rviz_projector
