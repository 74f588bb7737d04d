#include "rviz_projector/displays/x_error_watch.h"

#include <cstdio>

#include <X11/Xlib.h>

namespace rviz_projector
{
using XErrorHandlerFn = int (*)(::Display*, XErrorEvent*);

struct XErrorWatchAccess
{
  static XErrorWatch* active;

  static int record(::Display* display, XErrorEvent* event)
  {
    if (active != nullptr)
    {
      char text[160] = "";
      XGetErrorText(display, event->error_code, text, sizeof text);
      char line[320];
      std::snprintf(line, sizeof line, "%s (request %d.%d, resource 0x%lx)", text,
                    static_cast<int>(event->request_code), static_cast<int>(event->minor_code),
                    event->resourceid);
      active->errors_.emplace_back(line);
    }
    return 0;
  }
};

XErrorWatch* XErrorWatchAccess::active = nullptr;

XErrorWatch::XErrorWatch()
{
  previous_handler_ = reinterpret_cast<void*>(XSetErrorHandler(&XErrorWatchAccess::record));
  XErrorWatchAccess::active = this;
}

XErrorWatch::~XErrorWatch()
{
  XErrorWatchAccess::active = nullptr;
  XSetErrorHandler(reinterpret_cast<XErrorHandlerFn>(previous_handler_));
}

void XErrorWatch::sync(void* display)
{
  if (display != nullptr)
  {
    XSync(static_cast<::Display*>(display), False);
  }
}
}  // namespace rviz_projector
