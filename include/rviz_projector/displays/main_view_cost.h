// Whether rviz's own main view is set up in a way known to starve the projector window: rviz
// renders its main view in the same (GUI) thread at its global frame rate, and its default 4x
// multisampling on a software OpenGL renderer (Mesa llvmpipe, as on robots without a GPU) keeps
// about a core busy by itself (README, Performance). The projector window then gets ~26 instead
// of 60 frames/s. rviz's --disable-anti-aliasing option removes that cost.
#pragma once

#include <string>

#include "rviz_projector/displays/render_policy.h"

namespace rviz
{
class DisplayContext;
}

namespace rviz_projector
{
/// True for OpenGL renderers that rasterise on the CPU (Mesa llvmpipe/softpipe/swr, Windows GDI).
bool isSoftwareRenderer(const std::string& gl_renderer);

/// A warning for the user when the main view multisamples (`fsaa` samples, 0 or 1 = none) on a
/// software renderer; empty when it does not.
std::string mainViewCostWarning(unsigned int fsaa, const std::string& gl_renderer);
/// The same for rviz's running main view (empty when rviz is embedded without one, and always
/// under projector_host's `policy`: it renders no main view). The owner gives the policy (a
/// display: the process's policy, the default).
std::string mainViewCostWarning(rviz::DisplayContext& context, const RenderPolicy& policy = processRenderPolicy());
}  // namespace rviz_projector
