// Whether an X server can be reached, checked before Qt (which aborts without a clear message).
#pragma once

#include <string>

namespace rviz_projector
{
/// Empty when $DISPLAY names a reachable X server; else a sentence for the user.
std::string xDisplayProblem();
/// Logs the X protocol errors of this process's Xlib connections (OGRE's and the GL driver's),
/// which Qt's handler otherwise drops: the first 20 of them, then every 1000th, each with its
/// request and error code. A projector window whose frames fail to reach the screen (e.g. a buffer
/// swap refused by the X server) then says why in the log. Install after QApplication.
void logXErrors();
}  // namespace rviz_projector
