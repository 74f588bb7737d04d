#include "host_projector_status.h"

#include <cmath>
#include <cstdio>

#include <rviz/properties/status_property.h>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_camera_health.h"

namespace rviz_projector
{
namespace
{
std::string seconds(double value)
{
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", value);
  return text;
}
}  // namespace

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
  const ProjectorCameraHealth health = projector.health();
  status.add("Enabled", projector.isEnabled());
  status.addf("Output frame rate (frames/s)", "%.1f", health.frame_rate_hz);
  status.add("Seconds since last frame", health.seconds_since_last_frame < 0.0 ?
                                             std::string("no frame yet") :
                                             seconds(health.seconds_since_last_frame));
  status.add("Frames rendered", health.frames_rendered);
  status.add("Frames skipped (nothing changed)", health.frames_skipped);
  status.add("Motion compensation", health.prediction);
  status.addf("Prediction ahead of newest tf (ms)", "%.1f", health.prediction_ms);
  status.addf("Render to mid-frame delay (ms)", "%.1f", health.photon_delay_ms);
  status.add("tf age (s)", std::isnan(health.tf_age_s) ? std::string("no pose") : seconds(health.tf_age_s));
  status.add("CameraInfo age (s)",
             std::isnan(health.camera_info_age_s) ? std::string("none received") : seconds(health.camera_info_age_s));
  status.add("Lens", health.has_lens);
  status.add("Pose", health.pose_ok);
  status.add("Blanked", health.blanked ? "yes: " + health.blank_reason : std::string("no"));
  status.add("Window shown", health.window_shown);
  status.add("Full screen", health.full_screen);
  status.add("Screen", health.screen_name.empty() ? std::string("none") : health.screen_name);
  status.add("Screen connected", health.screen_connected);
  status.addf("Window size (px)", "%dx%d", health.window_width, health.window_height);
  status.addf("Drawn size (px)", "%dx%d", health.drawn_width, health.drawn_height);
  status.addf("Image in the window (px)", "%dx%d+%d+%d", health.image_width, health.image_height, health.image_left,
              health.image_top);
  unsigned char level = diagnostic_msgs::DiagnosticStatus::OK;
  if (worst == rviz::StatusProperty::Warn)
  {
    level = diagnostic_msgs::DiagnosticStatus::WARN;
  }
  else if (worst >= rviz::StatusProperty::Error)
  {
    level = diagnostic_msgs::DiagnosticStatus::ERROR;
  }
  if (projector.isEnabled() && !health.screen_connected && level < diagnostic_msgs::DiagnosticStatus::ERROR)
  {
    level = diagnostic_msgs::DiagnosticStatus::ERROR;
    summary = "no screen: the output window is not shown";
  }
  status.summary(level, summary);
}
}  // namespace rviz_projector
