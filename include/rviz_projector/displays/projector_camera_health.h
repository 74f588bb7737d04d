// What a ProjectorCamera is doing right now, in plain numbers (ProjectorCameraDisplay::health()):
// for diagnostics (projector_host publishes it) and for tests. No Qt, OGRE or ROS types.
#pragma once

#include <cstdint>
#include <string>

namespace rviz_projector
{
struct ProjectorCameraHealth
{
  double frame_rate_hz = 0.0;             ///< frames actually rendered per second, over the last ~2 s
  double seconds_since_last_frame = -1.0;  ///< since the last rendered frame; < 0 when none yet
  double tf_age_s = 0.0;                  ///< age of the pose's tf (NaN when no pose; 0 for a static chain)
  double camera_info_age_s = 0.0;         ///< since the last CameraInfo arrived (NaN when none received)
  std::uint64_t camera_info_messages = 0; ///< CameraInfo messages handled (repeats of the same lens included)
  bool has_lens = false;                  ///< a usable lens from the CameraInfo
  bool pose_ok = false;                   ///< a fresh pose: the scene is drawn from it
  bool blanked = true;                    ///< the projector shows no scene (background only, or nothing)
  std::string blank_reason;               ///< why, as the display's status says it (empty when not blanked)
  bool window_shown = false;              ///< the output window is shown
  bool full_screen = false;               ///< ... full screen
  std::string screen_name;                ///< screen it is shown on (empty while hidden)
  bool screen_connected = false;          ///< that screen is (still) connected
  int window_width = 0;                   ///< the output window's drawing area, in screen pixels
  int window_height = 0;
  int drawn_width = 0;                    ///< the size OGRE draws at (its render window): should equal
  int drawn_height = 0;                   ///< the window's; a mismatch means frames that miss the screen
  int image_left = 0;                     ///< where the projector image lands in the window (letterbox)
  int image_top = 0;
  int image_width = 0;
  int image_height = 0;
  std::uint64_t frames_rendered = 0;      ///< frames rendered into the output window so far
  std::uint64_t frames_skipped = 0;       ///< timer ticks that needed no new frame
  bool motion_compensation = false;       ///< Motion compensation is enabled
  std::string prediction;                 ///< what the last frame's prediction did (its Prediction line)
  double prediction_ms = 0.0;             ///< how far ahead of the newest pose it predicted (0: not)
  double photon_delay_ms = 0.0;           ///< measured lookup -> middle of the frame's time on screen
};
}  // namespace rviz_projector
