// Whether this process is projector_host (robot mode): rviz's displays run without rviz's main
// window, and nothing renders a main 3D view. The displays of this package adapt where rviz's GUI
// made a difference; projector_host sets it once, before it creates any display.
#pragma once

#include <cstdint>

namespace rviz_projector
{
/// What changes in host mode:
/// - the projector window may go full screen on the only screen (there is no rviz window to cover);
/// - the "Main view" cost warning is never raised (no main view is rendered);
/// - a ProjectorCamera that shows displays of other packages renders only when their scene changed
///   (projector_host counts every display's render request and the ProjectionGate compares the
///   scene graph of those displays), plus a keep-alive frame (kHostKeepAliveSeconds) for displays
///   that change their content without either.
void setHostMode(bool enabled);
bool hostMode();

/// projector_host counts here every render request of any display (rviz's queueRender()). A
/// projector takes it into account only while it shows displays of other packages: requests of
/// displays it does not show (rviz's TF display asks on every update) must not cost frames.
void countHostRenderRequest();
std::uint64_t hostRenderRequests();

/// In host mode, the longest a projector showing displays of other packages goes without a frame.
constexpr double kHostKeepAliveSeconds = 1.0;
}  // namespace rviz_projector
