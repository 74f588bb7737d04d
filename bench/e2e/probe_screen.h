// The e2e probe's eyes: the watched rectangle of the X screen, grabbed with MIT-SHM, and the
// XDamage events (or polling) that say when the X server drew into it.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <poll.h>
#include <sys/ipc.h>
#include <sys/shm.h>

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>
#include <X11/extensions/Xdamage.h>
#include <X11/extensions/Xfixes.h>

#include "probe_common.h"
#include "x11_windows.h"

namespace bench_probe
{
// ---- X11: the watched rectangle -----------------------------------------------------------
struct Rect
{
  int x = 0, y = 0, width = 0, height = 0;
};

class ShmGrab
{
public:
  ShmGrab(Display* display, const Rect& rect) : display_(display), rect_(rect)
  {
    const int screen = DefaultScreen(display_);
    image_ = XShmCreateImage(display_, DefaultVisual(display_, screen), static_cast<unsigned>(DefaultDepth(display_, screen)),
                             ZPixmap, nullptr, &info_, static_cast<unsigned>(rect.width),
                             static_cast<unsigned>(rect.height));
    if (!image_) fail("XShmCreateImage failed");
    info_.shmid = shmget(IPC_PRIVATE, static_cast<std::size_t>(image_->bytes_per_line) * image_->height, IPC_CREAT | 0600);
    if (info_.shmid < 0) fail("shmget failed");
    info_.shmaddr = image_->data = static_cast<char*>(shmat(info_.shmid, nullptr, 0));
    info_.readOnly = False;
    if (!XShmAttach(display_, &info_)) fail("XShmAttach failed");
    XSync(display_, False);
    shmctl(info_.shmid, IPC_RMID, nullptr);  // freed once both sides detach
  }
  ~ShmGrab()
  {
    XShmDetach(display_, &info_);
    XSync(display_, False);
    shmdt(info_.shmaddr);
    image_->data = nullptr;
    XDestroyImage(image_);
  }
  ShmGrab(const ShmGrab&) = delete;
  ShmGrab& operator=(const ShmGrab&) = delete;

  /// Reads the rectangle of the screen (root window: what is shown there, whichever window).
  void grab()
  {
    if (!XShmGetImage(display_, DefaultRootWindow(display_), image_, rect_.x, rect_.y, AllPlanes))
    {
      fail("XShmGetImage failed");
    }
  }
  const char* data() const { return image_->data; }
  std::size_t bytes() const { return static_cast<std::size_t>(image_->bytes_per_line) * image_->height; }
  XImage* image() const { return image_; }

private:
  Display* display_;
  Rect rect_;
  XImage* image_ = nullptr;
  XShmSegmentInfo info_{};
};

class WatchedScreen
{
public:
  explicit WatchedScreen(double poll_ms) : poll_ms_(poll_ms)
  {
    display_ = XOpenDisplay(nullptr);
    if (!display_) fail("cannot open the X display (DISPLAY unset?)");
    if (!XShmQueryExtension(display_)) fail("the X server has no MIT-SHM extension");
    int error_base = 0;
    if (poll_ms_ <= 0.0)
    {
      int fixes_event = 0, fixes_error = 0;
      if (!XDamageQueryExtension(display_, &damage_event_, &error_base) ||
          !XFixesQueryExtension(display_, &fixes_event, &fixes_error))
      {
        note("no XDamage/XFixes: polling every 2 ms instead");
        poll_ms_ = 2.0;
      }
    }
    root_ = DefaultRootWindow(display_);
    XWindowAttributes attributes;
    XGetWindowAttributes(display_, root_, &attributes);
    root_rect_ = Rect{0, 0, attributes.width, attributes.height};
  }
  ~WatchedScreen()
  {
    grabs_[0].reset();
    grabs_[1].reset();
    if (damage_) XDamageDestroy(display_, damage_);
    if (parts_) XFixesDestroyRegion(display_, parts_);
    XCloseDisplay(display_);
  }

  Display* display() const { return display_; }

  /// The largest viewable window whose title contains `title`, or 0.
  Window findWindow(const std::string& title)
  {
    return bench_x11::findLargestWindow(display_, root_, title);
  }

  Rect windowRect(Window window)
  {
    XWindowAttributes a;
    XGetWindowAttributes(display_, window, &a);
    int x = 0, y = 0;
    Window child;
    XTranslateCoordinates(display_, window, root_, 0, 0, &x, &y, &child);
    return Rect{x, y, a.width, a.height};
  }

  Rect clipToScreen(const Rect& r) const
  {
    const int x0 = std::max(r.x, 0), y0 = std::max(r.y, 0);
    const int x1 = std::min(r.x + r.width, root_rect_.width), y1 = std::min(r.y + r.height, root_rect_.height);
    return Rect{x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
  }

  /// Starts watching a rectangle of the screen.
  void watch(const Rect& rect)
  {
    rect_ = rect;
    grabs_[0] = std::make_unique<ShmGrab>(display_, rect_);
    grabs_[1] = std::make_unique<ShmGrab>(display_, rect_);
    current_ = 0;
    if (poll_ms_ <= 0.0 && !damage_)
    {
      damage_ = XDamageCreate(display_, root_, XDamageReportNonEmpty);
      parts_ = XFixesCreateRegion(display_, nullptr, 0);
    }
    XSync(display_, False);
    grabs_[current_]->grab();
  }

  /// Grabs a whole rectangle once (for finding the image in a window).
  std::vector<std::uint32_t> snapshot(const Rect& rect)
  {
    ShmGrab grab(display_, rect);
    grab.grab();
    std::vector<std::uint32_t> pixels(static_cast<std::size_t>(rect.width) * rect.height);
    for (int y = 0; y < rect.height; ++y)
    {
      for (int x = 0; x < rect.width; ++x)
      {
        pixels[static_cast<std::size_t>(y) * rect.width + x] = static_cast<std::uint32_t>(XGetPixel(grab.image(), x, y));
      }
    }
    return pixels;
  }

  struct Event
  {
    Clock::time_point time;  // when the server told us it drew (or when we polled)
    bool changed;            // any pixel of the rectangle differs from the previous grab
  };

  /**
   * Waits until the watched rectangle was drawn into (or the deadline); grabs it and says whether
   * its content changed. Returns false at the deadline.
   */
  bool next(Clock::time_point deadline, Event& event)
  {
    if (poll_ms_ > 0.0)
    {
      const auto due = last_poll_ + std::chrono::microseconds(static_cast<long>(poll_ms_ * 1000.0));
      const auto wake = std::min(due, deadline);
      std::this_thread::sleep_until(wake);
      if (wake == deadline && due > deadline)
      {
        return false;
      }
      last_poll_ = Clock::now();
      event.time = last_poll_;
      event.changed = grabAndCompare();
      ++draws_;
      return true;
    }
    while (true)
    {
      if (!waitForDamage(deadline))
      {
        return false;
      }
      const Clock::time_point time = Clock::now();
      if (!damageTouchesRect())
      {
        continue;
      }
      event.time = time;
      event.changed = grabAndCompare();
      ++draws_;
      return true;
    }
  }

  /// Draw operations seen in the rectangle so far (frames presented, changed or not).
  long draws() const { return draws_; }

private:
  bool waitForDamage(Clock::time_point deadline)
  {
    while (true)
    {
      while (XPending(display_) > 0)
      {
        XEvent e;
        XNextEvent(display_, &e);
        if (e.type == damage_event_ + XDamageNotify)
        {
          // Drain whatever else is queued, then take the whole accumulated damage at once.
          while (XPending(display_) > 0)
          {
            XNextEvent(display_, &e);
          }
          return true;
        }
      }
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0)
      {
        return false;
      }
      pollfd fd{ConnectionNumber(display_), POLLIN, 0};
      poll(&fd, 1, static_cast<int>(std::min<long long>(left, 100)));
    }
  }

  bool damageTouchesRect()
  {
    XDamageSubtract(display_, damage_, None, parts_);
    int count = 0;
    XRectangle* rects = XFixesFetchRegion(display_, parts_, &count);
    bool touches = false;
    for (int i = 0; i < count && !touches; ++i)
    {
      const XRectangle& r = rects[i];
      touches = r.x < rect_.x + rect_.width && r.x + r.width > rect_.x && r.y < rect_.y + rect_.height &&
                r.y + r.height > rect_.y;
    }
    if (rects) XFree(rects);
    return touches;
  }

  bool grabAndCompare()
  {
    const int next = 1 - current_;
    grabs_[next]->grab();
    const bool changed = std::memcmp(grabs_[next]->data(), grabs_[current_]->data(), grabs_[next]->bytes()) != 0;
    current_ = next;
    return changed;
  }

  Display* display_ = nullptr;
  Window root_ = 0;
  Rect root_rect_;
  Rect rect_;
  double poll_ms_;
  int damage_event_ = 0;
  Damage damage_ = 0;
  XserverRegion parts_ = 0;
  std::unique_ptr<ShmGrab> grabs_[2];
  int current_ = 0;
  long draws_ = 0;
  Clock::time_point last_poll_ = Clock::now();
};
}  // namespace bench_probe
