// ProjectorCameraDisplay::health(): gathered from what the display and its parts already know
// (the frame counters and FrameRateMeter, the last pose's tf age, the lens source's receive time,
// the output window and its screen, the statuses that say why nothing is drawn).
#include <cmath>
#include <limits>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output.h"
#include "rviz_projector/displays/projector_output_window.h"

namespace rviz_projector
{
ProjectorCameraHealth ProjectorCameraDisplay::health() const
{
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  ProjectorCameraHealth h;
  const double now = clock_.isValid() ? static_cast<double>(clock_.nsecsElapsed()) * 1e-9 : 0.0;
  h.frame_rate_hz = rate_meter_.rate(now);
  h.seconds_since_last_frame = rate_meter_.sinceLastFrame(now);
  h.frames_rendered = frames_rendered_;
  h.frames_skipped = frames_skipped_;
  h.has_lens = hasLens();
  h.tf_age_s = hasLens() ? tf_age_ : kNone;  // the pose is looked up only with a lens
  h.camera_info_age_s = lens_source_.secondsSinceInfo();
  h.pose_ok = hasLens() && pose_ok_;
  if (output_)
  {
    h.window_shown = output_->isShown();
    h.full_screen = h.window_shown && output_->window() && output_->window()->isFullScreenOn();
    h.screen_name = output_->shownScreen();
    h.screen_connected = !h.screen_name.empty() && ProjectorOutput::screenConnected(h.screen_name);
  }
  // The scene (or the crosshairs) is drawn only with a lens and a fresh pose: renderNow()'s rule.
  const auto status = [this](const char* name) {
    const auto it = status_cache_.find(name);
    return it == status_cache_.end() ? std::string() : it->second.second.toStdString();
  };
  h.blanked = true;
  if (!isEnabled())
  {
    h.blank_reason = "display disabled";
  }
  else if (!h.window_shown)
  {
    h.blank_reason = "output window not shown: " + status("Output");
  }
  else if (!hasLens())
  {
    h.blank_reason = status("CameraInfo");
  }
  else if (!pose_ok_ && !crosshairs_shown_)
  {
    h.blank_reason = status("Transform");
  }
  else
  {
    h.blanked = false;
  }
  return h;
}
}  // namespace rviz_projector
