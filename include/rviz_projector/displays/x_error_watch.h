// Xlib protocol errors of this process, recorded around one call: the creation of an OGRE render
// window (ProjectorRenderWidget). OGRE creates the window on one X connection and the GL driver
// (Mesa) uses it on another; on a loaded machine the X server can take the driver's first requests
// before the window's creation and refuse them (BadDrawable, then BadGC on every buffer swap): the
// frames are rendered, but none ever reaches the window. Seen in CI about once in four runs
// (27 Nov 2026, projector_host's X error log: GLX GetDrawableAttributes, CreateGC and GetGeometry
// refused on the new window, then every MIT-SHM PutImage). The widget creates the window again.
// Xlib lives in this file only (its macros clash with Qt and OGRE). GUI thread only; one watch at a
// time (Xlib's handler is process-wide: the previous one is restored).
#pragma once

#include <string>
#include <vector>

namespace rviz_projector
{
class XErrorWatch
{
public:
  XErrorWatch();
  ~XErrorWatch();
  XErrorWatch(const XErrorWatch&) = delete;
  XErrorWatch& operator=(const XErrorWatch&) = delete;

  /// Waits until the X server has answered every request sent so far on `display` (an Xlib
  /// `Display*`, e.g. OGRE's "XDISPLAY" or "DISPLAY" attribute; null: nothing): their errors are
  /// recorded by then.
  void sync(void* display);
  /// The errors recorded, one sentence each (empty: none).
  const std::vector<std::string>& errors() const { return errors_; }

private:
  friend struct XErrorWatchAccess;
  std::vector<std::string> errors_;
  void* previous_handler_ = nullptr;
};
}  // namespace rviz_projector
