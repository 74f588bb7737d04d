// One ProjectorCamera's diagnostic status for projector_host: its health (frame rate, last frame,
// tf and CameraInfo age, screen) and the statuses rviz would show for it.
#pragma once

#ifndef Q_MOC_RUN
#include <vector>

#include <diagnostic_updater/DiagnosticStatusWrapper.h>

#include "host_display_status.h"
#endif

namespace rviz_projector
{
class ProjectorCameraDisplay;

/// Level: the worst of the display's statuses (Error when it is disabled or blanked by stale data
/// is reported by its statuses too); message: the worst status line, or "projecting".
void fillProjectorStatus(const ProjectorCameraDisplay& projector, const std::vector<DisplayStatusLine>& lines,
                         diagnostic_updater::DiagnosticStatusWrapper& status);
}  // namespace rviz_projector
