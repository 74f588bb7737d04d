// A lower-case copy of a name or setting compared without regard to case: environment settings,
// OpenGL renderer and render system names, parameters, file extensions (ASCII: none of them is
// localised).
#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace rviz_projector
{
inline std::string asciiLower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}
}  // namespace rviz_projector
