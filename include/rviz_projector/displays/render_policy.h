// How the displays' parts render: under rviz (its main window and main view exist) or in
// projector_host (robot mode: rviz's displays without rviz's main window, no main view rendered).
// The parts that differ take a RenderPolicy from their owner (ProjectionGate, ProjectorOutput,
// mainViewCostWarning), so each can be tested with either policy. The displays are created by
// pluginlib with default constructors and cannot be handed one: they take the process's policy
// (processRenderPolicy()), which projector_host sets once, before it creates any display.
#pragma once

namespace rviz_projector
{
/// In projector_host, the longest a projector showing displays of other packages goes without a
/// frame by default (projector_host --keep-alive; 0: never, only scene-graph changes render).
constexpr double kHostKeepAliveSeconds = 1.0;

/// What changes in projector_host (host = true):
/// - the projector window may go full screen on the only screen (there is no rviz window to cover;
///   ProjectorOutput);
/// - the "Main view" cost warning is never raised (no main view is rendered; mainViewCostWarning);
/// - a ProjectorCamera that shows displays of other packages renders only when their scene graph
///   changed (node poses, visibility, bounds: scene_signature.h), plus a keep-alive frame every
///   `keep_alive_s` for content they change in place (ProjectionGate). rviz's render requests
///   (queueRender) cannot serve: they do not say which display asks, and some ask on every update
///   (the TF display, every view controller).
struct RenderPolicy
{
  bool host = false;
  /// Host only: seconds; 0 = no keep-alive frames.
  double keep_alive_s = kHostKeepAliveSeconds;

  /// rviz's policy (the default).
  static RenderPolicy rviz() { return RenderPolicy(); }
  /// projector_host's policy; a negative keep-alive counts as 0.
  static RenderPolicy projectorHost(double keep_alive_s = kHostKeepAliveSeconds)
  {
    RenderPolicy policy;
    policy.host = true;
    policy.keep_alive_s = keep_alive_s > 0.0 ? keep_alive_s : 0.0;
    return policy;
  }
};

/// The process's policy, what the displays give their parts: rviz's unless projector_host set
/// its own. The one place it is kept (in the plugin library: projector_host links the library that
/// pluginlib loads, so both see the same value).
RenderPolicy processRenderPolicy();
/// projector_host only, once, before it creates any display (a display's parts keep the policy
/// they were given).
void setProcessRenderPolicy(const RenderPolicy& policy);
}  // namespace rviz_projector
