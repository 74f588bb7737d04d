// Shared by the e2e benchmark's probes (bench_probe, slip_probe): finding a window by its title.
#pragma once

#include <string>

#include <X11/Xlib.h>

namespace bench_x11
{
/// The largest viewable window below `top` (itself included) whose title contains `title`, or 0.
Window findLargestWindow(Display* display, Window top, const std::string& title);
}  // namespace bench_x11
