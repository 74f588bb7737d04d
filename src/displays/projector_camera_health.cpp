// ProjectorCameraDisplay::health(): gathered from what the display and its parts already know
// (the frame counters and ProjectorFrameClock, the last pose's tf age, the lens source's receive time,
// the output window and its screen, the statuses that say why nothing is drawn).
#include <cmath>
#include <limits>

#include <OgreRenderWindow.h>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output.h"
#include "rviz_projector/displays/projector_output_window.h"

namespace rviz_projector
{
ProjectorCameraHealth ProjectorCameraDisplay::health() const
{
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  ProjectorCameraHealth h;
  h.frame_rate_hz = frame_clock_.frameRate();
  h.seconds_since_last_frame = frame_clock_.sinceLastFrame();
  h.frames_rendered = frames_rendered_;
  h.frames_skipped = frames_skipped_;
  h.motion_compensation = props_.motion_enabled->getBool();
  const Prediction& prediction = motion().lastPrediction();
  h.prediction = h.motion_compensation ? describePrediction(prediction) : std::string("off");
  h.prediction_ms = h.motion_compensation && prediction.extrapolated() ? prediction.horizon * 1e3 : 0.0;
  h.photon_delay_ms = motion().photonDelay(frame_clock_.period()) * 1e3;
  h.has_lens = hasLens();
  h.tf_age_s = hasLens() ? pipeline_.poseFollower().tfAge() : kNone;  // the pose is looked up only with a lens
  h.camera_info_age_s = pipeline_.lensSource().secondsSinceInfo();
  h.camera_info_messages = pipeline_.lensSource().messagesReceived();
  h.pose_ok = hasLens() && pipeline_.poseOk();
  if (output_)
  {
    h.window_shown = output_->isShown();
    h.full_screen = h.window_shown && output_->window() && output_->window()->isFullScreenOn();
    h.screen_name = output_->shownScreen();
    h.screen_connected = !h.screen_name.empty() && ProjectorOutput::screenConnected(h.screen_name);
    if (const Ogre::RenderWindow* rw = output_->renderWindow())
    {
      h.drawn_width = static_cast<int>(rw->getWidth());
      h.drawn_height = static_cast<int>(rw->getHeight());
    }
    if (const ProjectorOutputWindow* window = output_->window())
    {
      const QSize pixels = window->drawingPixels();
      h.window_width = pixels.width();
      h.window_height = pixels.height();
    }
    const PixelRect image = output_->imageRect();
    h.image_left = image.left;
    h.image_top = image.top;
    h.image_width = image.width;
    h.image_height = image.height;
  }
  // The scene (or the crosshairs) is drawn only with a lens and a fresh pose: renderNow()'s rule.
  const auto status = [this](const char* name) { return statuses_.text(name).toStdString(); };
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
  else if (!pipeline_.poseOk() && !crosshairs_shown_)
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
