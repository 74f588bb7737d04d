// The projector's output: a frameless top-level window holding an OGRE render window, full screen
// on the projector's screen. Owned by ProjectorCameraDisplay; never a dock panel of rviz (rviz
// disables a display whose panel gets hidden, e.g. when its main window is minimised).
#pragma once

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

  /**
   * Shows the window on `screen`: full screen (cursor hidden) if built so, else as a normal window
   * of `image_size` shrunk to fit the screen, centred, or with `corner` shrunk to at most half
   * the screen in its bottom-right corner (when it shares the screen with rviz). Moves to the
   * screen before going full screen.
   */
  void present(QScreen* screen, const QSize& image_size, bool corner = false);
  bool isFullScreenOn() const { return full_screen_; }
  int fsaa() const { return fsaa_; }

Q_SIGNALS:
  /// The user pressed Esc in full screen.
  void leaveFullScreenRequested();
  /// The user closed the window (window manager close button, Alt+F4).
  void closedByUser();

protected:
  void keyPressEvent(QKeyEvent* event) override;
  void closeEvent(QCloseEvent* event) override;

private:
  ProjectorRenderWidget* render_widget_;
  bool full_screen_ = false;
  int fsaa_ = 0;
};
}  // namespace rviz_projector
