// X11 side of the motion slip probe (bench/e2e/slip_probe.cpp): finds the projector's output
// window, works out where the projector image lies in it (letterboxed, as the ProjectorCamera
// draws it), and reads one screen row at a time with MIT-SHM.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>

namespace slip
{
struct ScreenRect
{
  int x = 0, y = 0, width = 0, height = 0;
};

/**
 * Where an image of image_w x image_h is shown in a window of the given size: uniform scale,
 * centred, black bars; 1:1 when it fits exactly along one axis and is no larger along the other
 * (the ProjectorCamera's documented rule, include/rviz_projector/core/letterbox.h, written out
 * again here so the probe does not measure with the code it measures). Relative to the window.
 */
ScreenRect imageRectInWindow(int image_w, int image_h, int window_w, int window_h);

class XScreen
{
public:
  XScreen();  // throws std::runtime_error without a display or MIT-SHM
  ~XScreen();
  XScreen(const XScreen&) = delete;
  XScreen& operator=(const XScreen&) = delete;

  /// The largest viewable window whose title contains `title`, or 0.
  Window findWindow(const std::string& title);
  /// The window's rectangle on the root window.
  ScreenRect windowRect(Window w);

  /// Starts reading row `y`, columns x .. x + width - 1 of the screen.
  void watchRow(int x, int y, int width);
  /// Reads the watched row; the pixels as 0xRRGGBB.
  const std::vector<std::uint32_t>& grabRow();

private:
  void releaseRow();

  Display* display_ = nullptr;
  XImage* image_ = nullptr;
  XShmSegmentInfo info_{};
  int x_ = 0, y_ = 0;
  std::vector<std::uint32_t> row_;
};
}  // namespace slip
