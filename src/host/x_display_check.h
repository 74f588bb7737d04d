// Whether an X server can be reached, checked before Qt (which aborts without a clear message).
#pragma once

#include <string>

namespace rviz_projector
{
/// Empty when $DISPLAY names a reachable X server; else a sentence for the user.
std::string xDisplayProblem();
}  // namespace rviz_projector
