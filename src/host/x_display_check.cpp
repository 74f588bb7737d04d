#include "x_display_check.h"

#include <cstdlib>

// Xlib in a file of its own: its macros (Bool, Status, None...) clash with Qt and rviz.
#include <X11/Xlib.h>

namespace rviz_projector
{
std::string xDisplayProblem()
{
  const char* name = std::getenv("DISPLAY");
  if (name == nullptr || *name == '\0')
  {
    return "no X display: $DISPLAY is not set. projector_host shows its windows on an X server on the "
           "projector's output (README, \"Running on the robot\": the desktop session or a bare Xorg)";
  }
  ::Display* display = XOpenDisplay(nullptr);
  if (display == nullptr)
  {
    return std::string("cannot open X display '") + name +
           "': is the X server running and may this user use it (XAUTHORITY)?";
  }
  XCloseDisplay(display);
  return std::string();
}
}  // namespace rviz_projector
