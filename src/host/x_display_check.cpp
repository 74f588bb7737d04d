#include "x_display_check.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>

// Xlib in a file of its own: its macros (Bool, Status, None...) clash with Qt and rviz.
#include <X11/Xlib.h>

namespace rviz_projector
{
namespace
{
std::atomic<unsigned long> x_errors{ 0 };

int logXError(::Display* display, XErrorEvent* event)
{
  const unsigned long n = ++x_errors;
  if (n <= 20 || n % 1000 == 0)
  {
    char text[160] = "";
    XGetErrorText(display, event->error_code, text, sizeof text);
    std::fprintf(stderr,
                 "projector_host: X error %lu: %s (error %d, request %d.%d, resource 0x%lx)%s\n", n, text,
                 static_cast<int>(event->error_code), static_cast<int>(event->request_code),
                 static_cast<int>(event->minor_code), event->resourceid,
                 n == 20 ? "; from now on only every 1000th is logged" : "");
  }
  return 0;  // as Qt's handler: the process goes on
}
}  // namespace

void logXErrors()
{
  XSetErrorHandler(logXError);
}

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
