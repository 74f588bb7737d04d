#include "x11_windows.h"

namespace bench_x11
{
namespace
{
void findIn(Display* d, Window w, const std::string& title, Window& best, long& best_area)
{
  char* name = nullptr;
  if (XFetchName(d, w, &name) && name)
  {
    const bool match = std::string(name).find(title) != std::string::npos;
    XFree(name);
    XWindowAttributes a;
    if (match && XGetWindowAttributes(d, w, &a) && a.map_state == IsViewable &&
        static_cast<long>(a.width) * a.height > best_area)
    {
      best = w;
      best_area = static_cast<long>(a.width) * a.height;
    }
  }
  Window root, parent;
  Window* children = nullptr;
  unsigned count = 0;
  if (XQueryTree(d, w, &root, &parent, &children, &count))
  {
    for (unsigned i = 0; i < count; ++i)
    {
      findIn(d, children[i], title, best, best_area);
    }
    if (children)
    {
      XFree(children);
    }
  }
}
}  // namespace

Window findLargestWindow(Display* display, Window top, const std::string& title)
{
  Window best = 0;
  long area = 0;
  findIn(display, top, title, best, area);
  return best;
}
}  // namespace bench_x11
