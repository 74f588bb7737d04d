// Whether this process is projector_host (robot mode): rviz's displays run without rviz's main
// window, and nothing renders a main 3D view. The displays of this package adapt where rviz's GUI
// made a difference; projector_host sets it once, before it creates any display.
#pragma once

namespace rviz_projector
{
/// What changes in host mode:
/// - the projector window may go full screen on the only screen (there is no rviz window to cover);
/// - the "Main view" cost warning is never raised (no main view is rendered);
/// - a ProjectorCamera that shows displays of other packages renders only when their scene graph
///   changed (node poses, visibility, bounds: scene_signature.h), plus a keep-alive frame
///   (hostKeepAliveSeconds()) for content they change in place. rviz's render requests
///   (queueRender) cannot serve: they do not say which display asks, and some ask on every update
///   (the TF display, every view controller).
void setHostMode(bool enabled);
bool hostMode();

/// In host mode, the longest a projector showing displays of other packages goes without a frame
/// (projector_host --keep-alive; 0: never, only scene-graph changes render).
constexpr double kHostKeepAliveSeconds = 1.0;
void setHostKeepAliveSeconds(double seconds);
double hostKeepAliveSeconds();
}  // namespace rviz_projector
