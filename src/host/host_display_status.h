// The statuses an rviz display shows in rviz's Displays panel (its "Status" list), read for
// projector_host's diagnostics: host_diagnostics (every display) and host_projector_status (one
// ProjectorCamera) both use them, and neither includes the other; and how the host names a display.
#pragma once

#include <string>
#include <vector>

namespace rviz
{
class Display;
}

namespace rviz_projector
{
/// One status line of an rviz display, as its Status list shows it.
struct DisplayStatusLine
{
  std::string name;
  int level = 0;  ///< rviz::StatusProperty::Level (Ok 0, Warn 1, Error 2)
  std::string text;
};

/// The status lines `display` shows in rviz's Displays panel (its "Status" list).
std::vector<DisplayStatusLine> displayStatusLines(const rviz::Display& display);

/// "Name (package/Class)": how the host's log and diagnostics name a display.
std::string displayLabel(const rviz::Display& display);
}  // namespace rviz_projector
