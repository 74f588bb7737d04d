// One part of ProjectorCameraDisplay: the projector's lens from its CameraInfo topic. The
// subscription lives on a callback queue of its own, drained by the display's frame timer: prompt,
// and never a reason to spin rviz's global queue (whose callbacks may delete the display).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

#include <QString>
#include <ros/ros.h>

#include "rviz_projector/displays/private_callback_queue.h"
#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/lens_check.h"
#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"

namespace rviz_projector
{
/// What the display's lens statuses say. An empty warning means: no such status.
struct LensStatuses
{
  enum Level
  {
    Ok,
    Warn,
    Error
  };
  Level camera_info_level = Warn;
  QString camera_info;    ///< "CameraInfo"
  QString distortion;     ///< "Distortion" (warn): a D that is not drawn
  QString distortion_drawn;  ///< "Distortion" (ok): the model and D that are drawn (issue 24)
  QString field_of_view;  ///< "Field of view" (warn)
};

/// What the CameraInfo messages handled by one poll() changed. Camera drivers and
/// camera_info_manager-style nodes publish the same CameraInfo with every frame: such a message
/// changes nothing (both false), so nothing is reset, rendered or repainted for it.
struct LensEvent
{
  bool lens = false;   ///< the lens values (size, K, P, D, binning, ROI, model) or their usability changed
  bool frame = false;  ///< the header's frame_id changed (the projector's pose is of another frame)
  bool any() const { return lens || frame; }
};

/// The lens a projector draws through, from its CameraInfo's values: P's pinhole and no distortion,
/// or with a D that can be drawn K's raw pinhole and that D. An error leaves `lens` unusable. Shared
/// by the ProjectorCamera and ProjectedPath's off-view cue (the same lit area).
LensCheck projectorLens(const LensCalibration& calibration, PinholeModel& lens, LensDistortion& distortion);

class ProjectorLensSource
{
public:
  ProjectorLensSource();
  ~ProjectorLensSource();
  ProjectorLensSource(const ProjectorLensSource&) = delete;
  ProjectorLensSource& operator=(const ProjectorLensSource&) = delete;

  /// Subscribes to `topic`; returns an error text (empty: subscribed).
  std::string subscribe(const std::string& topic);
  void unsubscribe();
  /// Forgets the last CameraInfo and its lens (the topic changed).
  void forget();
  /// Handles the CameraInfo messages that arrived since the last call: what they changed.
  LensEvent poll();
  /// CameraInfo messages received since subscribe()/forget(), changed or not (tests, health).
  std::uint64_t messagesReceived() const { return messages_; }

  bool hasInfo() const { return static_cast<bool>(last_); }
  /// A usable lens from the last CameraInfo.
  bool hasLens() const { return has_lens_; }
  /// The lens's pixels: P's pinhole; with a distortion that is drawn, K's (the raw pixels, as
  /// cv::projectPoints with K and D maps them).
  const PinholeModel& lens() const { return lens_; }
  /// The distortion to draw through (none when D is zero or cannot be drawn: see statuses()).
  const LensDistortion& distortion() const { return distortion_; }
  /// "plumb_bob, D = k1 k2 ..." of the distortion drawn ("" when none).
  QString distortionDrawn() const;
  /// Seconds since the last CameraInfo arrived (steady clock; NaN without one).
  double secondsSinceInfo() const;
  /// frame_id of the last CameraInfo (empty without one).
  const std::string& frameId() const { return frame_id_; }
  /// The statuses for the display; `topic` names the topic in "No CameraInfo received".
  LensStatuses statuses(const QString& topic) const;

private:
  void callback(const sensor_msgs::CameraInfo::ConstPtr& msg);

  // Declared before the subscriber: the subscription goes first, its queue after it.
  PrivateCallbackQueue queue_;  ///< drained by the projector's frame clock (paused while disabled)
  ros::NodeHandle nh_;
  ros::Subscriber sub_;
  sensor_msgs::CameraInfo::ConstPtr last_;
  std::chrono::steady_clock::time_point last_received_;  ///< when last_ arrived
  LensEvent event_;                ///< what the messages handled in this poll() changed
  std::uint64_t messages_ = 0;
  LensCalibration calibration_;    ///< the values of last_ (compared with each new message)
  std::string frame_id_;
  PinholeModel lens_;
  bool has_lens_ = false;
  LensCheck check_;
  LensDistortion distortion_;
  std::string narrow_view_;
};
}  // namespace rviz_projector
