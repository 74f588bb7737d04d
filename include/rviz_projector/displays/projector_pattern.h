// One part of ProjectorCameraDisplay (issue 24): the Pattern topic. Any node can put an image on
// the projector 1:1, full screen, instead of the scene: `calibrate_projector --camera` shows its
// structured-light patterns this way, in rviz or in projector_host.
//
// The interface (doc/reference/displays.md, "Pattern topic"):
//  - sensor_msgs/Image on the Pattern topic (default /projector/pattern), exactly the lens's
//    width x height (the CameraInfo's image after binning/ROI), mono8, rgb8, bgr8, rgba8 or bgra8:
//    shown pixel for pixel (pixel (u, v) of the image lights projector pixel (u, v); no scaling,
//    no distortion warp, no scene).
//  - an Image of 0 x 0 ends it: the scene comes back.
//  - Pattern timeout (seconds, 0 = never): no new pattern for that long ends it too, so a crashed
//    calibration never leaves the projector showing stripes.
//  - std_msgs/Header on <Pattern topic>/shown: the header of the pattern (stamp, frame_id, seq as
//    received) once the frame showing it went to the screen; also for the 0 x 0 image (the scene is
//    back). A sender matches it by stamp; the projector's own lag (up to a frame of the screen) and
//    the camera's exposure come after it: wait a settle time before capturing.
// Newest wins: patterns that arrive faster than frames are skipped (and never acknowledged).
//
// Like the crosshairs, the pattern is a quad in image space in a scene manager of its own, seen
// only by this part's camera: rviz's main view can never show it.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include <OgreMaterial.h>
#include <OgreTexture.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Header.h>

#include "rviz_projector/displays/private_callback_queue.h"

namespace Ogre
{
class Camera;
class ManualObject;
class SceneManager;
}  // namespace Ogre

namespace rviz_projector
{
/// The pixels of a pattern image as tightly packed BGRA rows (what the texture takes), or why it
/// cannot be shown: an encoding other than mono8/rgb8/bgr8/rgba8/bgra8, a step shorter than a row,
/// data shorter than height x step. Shows the size check too (width x height must be the lens's).
std::string patternPixels(const sensor_msgs::Image& image, std::uint32_t width, std::uint32_t height,
                          std::vector<std::uint8_t>& bgra);

class ProjectorPattern
{
public:
  enum class Level
  {
    None,  ///< no pattern: no status
    Ok,
    Warn,
    Error
  };
  using SteadyTime = std::chrono::steady_clock::time_point;

  ProjectorPattern();
  ~ProjectorPattern();
  ProjectorPattern(const ProjectorPattern&) = delete;
  ProjectorPattern& operator=(const ProjectorPattern&) = delete;

  /// Subscribes to `topic` (on this part's own queue) and advertises `topic`/shown; an empty topic
  /// turns the interface off. Drops any pattern shown. Returns an error text (empty: fine).
  std::string subscribe(const std::string& topic);
  void unsubscribe();

  /**
   * Handles what arrived (the newest image wins) and the timeout, for a lens of width x height
   * (0 x 0: no lens yet; a pattern then waits). Returns true when what the projector must show
   * changed (a new pattern, or back to the scene).
   */
  bool poll(std::uint32_t width, std::uint32_t height, double timeout_seconds, SteadyTime now);
  /// A pattern is on the projector instead of the scene.
  bool shown() const { return shown_; }
  /// The camera the projector's viewport uses while a pattern is shown.
  Ogre::Camera* camera() const { return camera_; }
  /// The frame showing the current state went to the screen (or already showed it): acknowledges it
  /// once on /shown.
  void frameShown();
  /// Ends the pattern shown, with an Error status `why`, never acknowledged (e.g. the output window
  /// would scale it).
  void refuse(const std::string& why);

  /// The "Pattern" status: level (None: no status) and text; `statusChanged()` since the last call.
  Level level() const { return level_; }
  const std::string& statusText() const { return status_; }
  bool takeStatusChange();
  /// Patterns received and acknowledged since subscribe() (tests, health).
  std::uint64_t received() const { return received_; }
  std::uint64_t acknowledged() const { return acknowledged_; }

private:
  void callback(const sensor_msgs::Image::ConstPtr& msg);
  /// Uploads `bgra` (width x height) into the texture, (re)made for that size.
  void upload(const std::vector<std::uint8_t>& bgra, std::uint32_t width, std::uint32_t height);
  void setStatus(Level level, const std::string& text);
  void end(const std::string& why, Level level);

  ros::NodeHandle nh_;
  PrivateCallbackQueue queue_;  ///< drained from poll(): the frame clock's thread
  ros::Subscriber sub_;
  ros::Publisher shown_pub_;
  std::string topic_;
  sensor_msgs::Image::ConstPtr pending_;  ///< newest arrival not handled yet

  Ogre::SceneManager* scene_manager_;
  Ogre::Camera* camera_;
  Ogre::ManualObject* quad_;
  Ogre::MaterialPtr material_;
  Ogre::TexturePtr texture_;

  bool shown_ = false;
  bool ack_due_ = false;
  std_msgs::Header ack_;
  SteadyTime last_pattern_{};
  Level level_ = Level::None;
  std::string status_;
  bool status_changed_ = false;
  std::uint64_t received_ = 0;
  std::uint64_t acknowledged_ = 0;
};
}  // namespace rviz_projector
