// The projector's output, one part of ProjectorCameraDisplay: the top-level output window, its OGRE
// render window and the viewport the projector's camera draws into; full screen or windowed, on
// which screen, and the exact letterbox of the image in the window. Returns what it did; the
// display turns that into its "Output" status.
#pragma once

#ifndef Q_MOC_RUN
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <OgreColourValue.h>
#include <QObject>
#include <QPointer>
#include <QRect>
#include <QString>

#include "rviz_projector/core/letterbox.h"
#include "rviz_projector/core/screen_choice.h"
#include "rviz_projector/displays/render_policy.h"
#endif

namespace Ogre
{
class Camera;
class RenderTargetListener;
class RenderWindow;
class Viewport;
}  // namespace Ogre
class QScreen;
class QWidget;

namespace rviz_projector
{
class ProjectorOutputWindow;

/// What the display wants shown.
struct OutputRequest
{
  std::string screen = kAutomaticScreen;  ///< a screen's name, or "Automatic"
  bool full_screen = true;
  int fsaa = 0;                      ///< multisampling samples, 0 = off
  std::uint32_t image_width = 0;     ///< 0: no lens yet (a 1280x800 window until one arrives)
  std::uint32_t image_height = 0;
  QScreen* rviz_screen = nullptr;    ///< the screen of rviz's main window (nullptr: unknown)
};

/// What the output did, for the "Output" status.
struct OutputResult
{
  enum Level
  {
    Ok,
    Warn,
    Error
  };
  Level level = Ok;
  QString text;
  bool shown = false;
};

class ProjectorOutput : public QObject
{
  Q_OBJECT
public:
  /// `camera` draws into the viewport; `listener` hears the render window's updates (both outlive
  /// this object). `policy` says whether an rviz window may need the screen (present()); the owner
  /// gives it (a display: the process's policy, the default).
  ProjectorOutput(const QString& title, Ogre::Camera* camera, Ogre::RenderTargetListener* listener,
                  const RenderPolicy& policy = processRenderPolicy());
  ~ProjectorOutput() override;

  /// Creates the window if needed (again when frame or multisampling must change), chooses the
  /// screen and shows the window there. Never throws: a window that cannot be created is an Error.
  OutputResult present(const OutputRequest& request);
  /// Title of the window ("Projector: <display name>").
  void setTitle(const QString& title);
  /// Hides the window (the floor goes dark); the window and its geometry are kept.
  void hide();
  /// Destroys the window (listener, viewport, render window, widget, in that order).
  void destroy();

  bool isShown() const;
  /// Name of the screen the window is shown on (empty while hidden).
  const std::string& shownScreen() const { return screen_name_; }
  /// Refresh rate of the screen the window is on, Hz (0 when unknown).
  double refreshRate() const;
  ProjectorOutputWindow* window() const { return window_.get(); }
  Ogre::RenderWindow* renderWindow() const;
  Ogre::Viewport* viewport() const { return viewport_; }
  /// Where the image is drawn in the window, window pixels (whole window without an image size).
  PixelRect imageRect() const { return image_rect_; }

  /// Whether the window system asked for the picture again since the last call (render even if
  /// nothing changed).
  bool takeRepaintRequest()
  {
    const bool requested = repaint_requested_;
    repaint_requested_ = false;
    return requested;
  }
  /// Fits the viewport to an image of this size in the current window, exactly to integer pixels.
  /// Returns true when the rectangle changed. Cheap when nothing changed (no OGRE call).
  bool fitViewport(std::uint32_t image_width, std::uint32_t image_height);
  void setBackground(const Ogre::ColourValue& colour);
  void setVisibilityMask(std::uint32_t mask);
  /// Renders the viewport into the back buffer; shows it when `swap`.
  void render(bool swap);
  /// Shows the back buffer (after render(false) and a read-back).
  void swap();

  /// The screen a widget's window is on (nullptr for none, e.g. rviz embedded without a window).
  static QScreen* screenOf(const QWidget* widget);
  /// The screen name in an Output screen property. Configs saved before 2026-11 hold a label
  /// "NAME (WxH at X,Y)": its name part.
  static std::string screenName(const QString& value);
  /// Whether a screen of that name is connected.
  static bool screenConnected(const std::string& name);
  /// Status text when the image is scaled in the window (not 1:1); empty when it is not.
  QString scalingNote(std::uint32_t image_width, std::uint32_t image_height) const;

  /// Screen names other projector outputs of this process are shown on.
  static std::vector<std::string> screensInUse(const ProjectorOutput* except);

Q_SIGNALS:
  /// The user pressed Esc in the full-screen window (delivered after the key handler returned).
  void leaveFullScreenRequested();
  /// The user closed the window (delivered after the close handler returned).
  void closedByUser();

private Q_SLOTS:
  void onApplicationQuit();

private:
  bool create(bool full_screen, int fsaa, QString& error);
  void rememberUserGeometry();

  QString title_;
  Ogre::Camera* camera_;
  Ogre::RenderTargetListener* listener_;
  RenderPolicy policy_;
  std::unique_ptr<ProjectorOutputWindow> window_;
  Ogre::Viewport* viewport_ = nullptr;
  Ogre::ColourValue background_ = Ogre::ColourValue::Black;
  std::uint32_t visibility_mask_ = 0;
  PixelRect image_rect_;
  int window_width_ = 0;
  int window_height_ = 0;
  std::string screen_name_;  ///< screen the window is on (empty while hidden)
  bool seen_several_screens_ = false;  ///< host policy: more than one screen was connected at some point
  QRect windowed_geometry_;
  QRect placed_geometry_;  ///< the windowed geometry last set here (anything else is the user's)
  bool repaint_requested_ = false;  ///< the user's windowed geometry, kept across full-screen toggles
};
}  // namespace rviz_projector
