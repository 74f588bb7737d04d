// The OGRE render window inside the projector's output window. Like rviz's RenderWidget, but with
// its own multisampling setting (rviz gives every window 4x FSAA, which on software or integrated
// GL costs most of a frame and buys nothing on a projected floor) and a complete teardown: the
// render window is detached from OGRE's root and destroyed, so rviz never renders into a window
// that is gone (removing camera-like displays is where rviz plugins historically crash).
#pragma once

#include <functional>
#include <string>

#include <QWidget>

namespace Ogre
{
class RenderWindow;
}

namespace rviz_projector
{
class ProjectorRenderWidget : public QWidget
{
public:
  /// `fsaa`: multisampling samples (0 = off).
  ProjectorRenderWidget(QWidget* parent, int fsaa);
  ~ProjectorRenderWidget() override;

  Ogre::RenderWindow* renderWindow() const { return render_window_; }
  /// Called when the window system asks for the picture again (exposed, un-minimised). The widget
  /// never renders by itself: rendering into a window that is still being mapped or resized
  /// crashed Mesa's software renderer; the display renders at its next frame instead.
  void setRepaintRequest(std::function<void()> request) { repaint_request_ = std::move(request); }
  /// Empty, or why frames may not reach the window: the X server kept refusing the GL driver's use
  /// of the render window (kCreateAttempts creations).
  const std::string& setupProblem() const { return setup_problem_; }
  /// Creations of the render window tried before giving up.
  static constexpr int kCreateAttempts = 4;

protected:
  void moveEvent(QMoveEvent* event) override;
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  QPaintEngine* paintEngine() const override { return nullptr; }

private:
  /// RVIZ_PROJECTOR_TEST_REFUSE_WINDOWS=N: the first N creations count as refused (tests of the
  /// recovery: the race itself cannot be made to happen on demand).
  static int testRefusals();
  void destroyRenderWindow();

  Ogre::RenderWindow* render_window_ = nullptr;
  std::string setup_problem_;
  std::function<void()> repaint_request_;
};
}  // namespace rviz_projector
