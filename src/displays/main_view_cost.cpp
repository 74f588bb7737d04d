#include "rviz_projector/displays/main_view_cost.h"

#include <algorithm>
#include <cctype>

namespace rviz_projector
{
bool isSoftwareRenderer(const std::string& gl_renderer)
{
  std::string name = gl_renderer;
  std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* software : {"llvmpipe", "softpipe", "software rasterizer", "swr", "gdi generic"})
  {
    if (name.find(software) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

std::string mainViewCostWarning(unsigned int fsaa, const std::string& gl_renderer)
{
  if (fsaa <= 1 || !isSoftwareRenderer(gl_renderer))
  {
    return std::string();
  }
  return "rviz's main view renders with " + std::to_string(fsaa) + "x anti-aliasing on a software renderer (" +
         gl_renderer +
         "): that alone keeps about a core busy and holds the projector window below its frame rate. Start rviz "
         "with --disable-anti-aliasing (demo.launch does), or lower Global Options > Frame Rate.";
}
}  // namespace rviz_projector
