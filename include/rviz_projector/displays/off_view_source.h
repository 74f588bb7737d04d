// Where the off-view cue's lit area comes from, and the cue itself: the projector's
// sensor_msgs/CameraInfo topic (on the display's private callback queue; the same topic the
// ProjectorCamera uses), its lens (projectorLens: distortion included) at the tf pose of the
// header's frame_id in the fixed frame -> the core's FloorFootprint -> its outline as the lit area
// -> the core's OffViewCue (which keeps the show/hide hysteresis). One part of
// ProjectedPathDisplay: it returns the cue for an instant and what the "Off-view cue" status says.
#pragma once

#ifndef Q_MOC_RUN
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <ros/node_handle.h>
#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/off_view_cue.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/displays/news_flag.h"
#include "rviz_projector/displays/path_cue_source.h"
#include "rviz_projector/displays/topic_subscription.h"
#endif

namespace rviz
{
class FrameManager;
}

namespace rviz_projector
{
class OffViewSource
{
public:
  /// Subscribes to `topic` with `nh` (whose callback queue the display drains); empty: none. The
  /// same topic again changes nothing.
  void subscribe(ros::NodeHandle& nh, const std::string& topic);
  void unsubscribe();
  /// Forgets the CameraInfo and the cue's state (a new topic).
  void clear();
  /// Forgets the cue's show/hide state and the lit area (rviz's Reset, a backward jump of ROS time,
  /// a property change), not the lens: a latched CameraInfo is not sent again.
  void resetCue()
  {
    cue_.reset();
    built_ = Key();
    lit_revision_ = ~0ull;
  }

  /**
   * The cue for this instant: the lit area from the last CameraInfo and the projector's latest tf
   * pose in the fixed frame (recomputed only when the lens or the pose changed), then
   * OffViewCue::build. `robot_known` false, or no usable lit area: an empty result (kind None, no
   * triangles) and the status says why. `path_id` identifies the path (the message drawn): with
   * the same path, robot, lit area and parameters as the last call, the last result is returned
   * without building it again (a standing robot costs nothing per frame).
   */
  const OffViewResult& cueAt(rviz::FrameManager& frames, const void* path_id, const std::vector<Vec2>& path,
                             const std::vector<double>& lengths, bool robot_known, const OffViewInput& robot,
                             const OffViewParameters& parameters);
  /// What the "Off-view cue" status says (after cueAt).
  const CueStatus& status() const { return status_; }
  /// The lit area of the last cueAt (empty when there was none), in the fixed frame.
  const std::vector<Vec2>& lit() const { return lit_; }
  /// How often OffViewCue::build ran (tests: not again while nothing changed).
  std::size_t builds() const { return builds_; }
  /// CameraInfo messages taken so far (tests wait for theirs).
  std::size_t messages() const { return messages_; }
  /// Whether a CameraInfo with a new lens or frame arrived since the last call.
  bool takeNews() { return news_.take(); }

private:
  void onInfo(const sensor_msgs::CameraInfo::ConstPtr& msg);
  /// Nothing drawn; the status says `why`.
  const OffViewResult& nothing(CueStatus::Level level, const std::string& why);

  TopicSubscription subscription_;
  bool received_ = false;
  std::string frame_id_;
  LensCalibration calibration_;
  PinholeModel lens_;
  LensDistortion distortion_;
  LensCheck check_;
  std::uint64_t lens_revision_ = 0;  ///< bumped for every new lens or frame
  std::uint64_t lit_revision_ = ~0ull;
  std::array<double, 7> lit_pose_{};  ///< the pose lit_ was computed for
  bool lit_complete_ = false;
  std::vector<Vec2> lit_;
  OffViewCue cue_;
  /// What the cue was last built from (built again only when one of these changed).
  struct Key
  {
    const void* path_id = nullptr;
    std::size_t path_size = 0;
    std::uint64_t lit_revision = ~0ull;
    std::array<double, 5> robot{};  ///< x, y, heading, start, drawn_from
    OffViewParameters parameters;
    bool operator==(const Key& o) const;
  } built_;
  std::uint64_t lit_changes_ = 0;  ///< bumped whenever lit_ is recomputed
  OffViewResult empty_;
  CueStatus status_;
  NewsFlag news_;
  std::size_t messages_ = 0;
  std::size_t builds_ = 0;
};
}  // namespace rviz_projector
