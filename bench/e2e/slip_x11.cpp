#include "slip_x11.h"

#include "x11_windows.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <sys/ipc.h>
#include <sys/shm.h>

namespace slip
{
ScreenRect imageRectInWindow(int image_w, int image_h, int window_w, int window_h)
{
  if (window_w <= 0 || window_h <= 0)
  {
    return ScreenRect{};
  }
  if (image_w <= 0 || image_h <= 0)
  {
    return ScreenRect{0, 0, window_w, window_h};
  }
  int w = image_w, h = image_h;
  const bool exact = (image_w == window_w && image_h <= window_h) || (image_h == window_h && image_w <= window_w);
  if (!exact)
  {
    const double scale = std::min(static_cast<double>(window_w) / image_w, static_cast<double>(window_h) / image_h);
    w = std::max(1, static_cast<int>(std::lround(image_w * scale)));
    h = std::max(1, static_cast<int>(std::lround(image_h * scale)));
  }
  return ScreenRect{(window_w - w) / 2, (window_h - h) / 2, w, h};
}

XScreen::XScreen()
{
  display_ = XOpenDisplay(nullptr);
  if (!display_)
  {
    throw std::runtime_error("cannot open the X display (DISPLAY unset?)");
  }
  if (!XShmQueryExtension(display_))
  {
    throw std::runtime_error("the X server has no MIT-SHM extension");
  }
}

XScreen::~XScreen()
{
  releaseRow();
  XCloseDisplay(display_);
}


Window XScreen::findWindow(const std::string& title)
{
  return bench_x11::findLargestWindow(display_, DefaultRootWindow(display_), title);
}

ScreenRect XScreen::windowRect(Window w)
{
  XWindowAttributes a;
  XGetWindowAttributes(display_, w, &a);
  int x = 0, y = 0;
  Window child;
  XTranslateCoordinates(display_, w, DefaultRootWindow(display_), 0, 0, &x, &y, &child);
  return ScreenRect{x, y, a.width, a.height};
}

void XScreen::watchRow(int x, int y, int width)
{
  releaseRow();
  const int screen = DefaultScreen(display_);
  image_ = XShmCreateImage(display_, DefaultVisual(display_, screen), static_cast<unsigned>(DefaultDepth(display_, screen)),
                           ZPixmap, nullptr, &info_, static_cast<unsigned>(width), 1u);
  if (!image_)
  {
    throw std::runtime_error("XShmCreateImage failed");
  }
  info_.shmid = shmget(IPC_PRIVATE, static_cast<std::size_t>(image_->bytes_per_line) * image_->height, IPC_CREAT | 0600);
  if (info_.shmid < 0)
  {
    throw std::runtime_error("shmget failed");
  }
  info_.shmaddr = image_->data = static_cast<char*>(shmat(info_.shmid, nullptr, 0));
  info_.readOnly = False;
  if (!XShmAttach(display_, &info_))
  {
    throw std::runtime_error("XShmAttach failed");
  }
  XSync(display_, False);
  shmctl(info_.shmid, IPC_RMID, nullptr);  // freed once both sides detach
  x_ = x;
  y_ = y;
  row_.assign(static_cast<std::size_t>(width), 0u);
}

const std::vector<std::uint32_t>& XScreen::grabRow()
{
  if (!image_ || !XShmGetImage(display_, DefaultRootWindow(display_), image_, x_, y_, AllPlanes))
  {
    throw std::runtime_error("XShmGetImage failed");
  }
  for (std::size_t i = 0; i < row_.size(); ++i)
  {
    row_[i] = static_cast<std::uint32_t>(XGetPixel(image_, static_cast<int>(i), 0)) & 0xFFFFFFu;
  }
  return row_;
}

void XScreen::releaseRow()
{
  if (!image_)
  {
    return;
  }
  XShmDetach(display_, &info_);
  XSync(display_, False);
  shmdt(info_.shmaddr);
  image_->data = nullptr;
  XDestroyImage(image_);
  image_ = nullptr;
}
}  // namespace slip
