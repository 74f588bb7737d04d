#include "rviz_projector/host/host_projector_status.h"

#include <rviz/properties/status_property.h>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/host/host_diagnostics.h"

namespace rviz_projector
{
void fillProjectorStatus(const ProjectorCameraDisplay& projector, const std::vector<DisplayStatusLine>& lines,
                         diagnostic_updater::DiagnosticStatusWrapper& status)
{
  int worst = rviz::StatusProperty::Ok;
  std::string summary = projector.isEnabled() ? "projecting" : "disabled";
  for (const DisplayStatusLine& line : lines)
  {
    status.add("Status / " + line.name, line.text);
    if (line.level > worst)
    {
      worst = line.level;
      summary = line.name + ": " + line.text;
    }
  }
  status.add("Enabled", projector.isEnabled());
  status.add("Frames rendered", projector.framesRendered());
  status.add("Frames skipped (nothing changed)", projector.framesSkipped());
  status.add("Lens", projector.hasLens());
  unsigned char level = diagnostic_msgs::DiagnosticStatus::OK;
  if (worst == rviz::StatusProperty::Warn)
  {
    level = diagnostic_msgs::DiagnosticStatus::WARN;
  }
  else if (worst >= rviz::StatusProperty::Error)
  {
    level = diagnostic_msgs::DiagnosticStatus::ERROR;
  }
  status.summary(level, summary);
}
}  // namespace rviz_projector
