#include "rviz_projector/displays/off_view_source.h"

#include <cmath>
#include <cstring>
#include <type_traits>

#include <OgreQuaternion.h>
#include <OgreVector3.h>
#include <rviz/frame_manager.h>

#include "rviz_projector/core/floor_footprint.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/displays/projector_lens_source.h"
#include "rviz_projector/displays/ros_clock.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
/// Rays of the lens are followed this far (metres): a lit area farther away is not a floor patch.
constexpr double kMaxThrow = 10.0;
}  // namespace

bool OffViewSource::Key::operator==(const Key& o) const
{
  // OffViewParameters holds doubles only: compared bit for bit.
  static_assert(std::is_trivially_copyable<OffViewParameters>::value &&
                    sizeof(OffViewParameters) % sizeof(double) == 0,
                "OffViewParameters: plain doubles");
  return path_id == o.path_id && path_size == o.path_size && lit_revision == o.lit_revision && robot == o.robot &&
         std::memcmp(&parameters, &o.parameters, sizeof(OffViewParameters)) == 0;
}

void OffViewSource::subscribe(ros::NodeHandle& nh, const std::string& topic)
{
  if (subscription_.subscribe(nh, topic, 1, &OffViewSource::onInfo, this, "Projector info"))
  {
    clear();
  }
}

void OffViewSource::unsubscribe()
{
  subscription_.shutdown();
  clear();
}

void OffViewSource::clear()
{
  received_ = false;
  frame_id_.clear();
  calibration_ = LensCalibration();
  check_ = LensCheck();
  ++lens_revision_;
  lit_.clear();
  resetCue();
}

void OffViewSource::onInfo(const sensor_msgs::CameraInfo::ConstPtr& msg)
{
  ++messages_;
  LensCalibration calibration = toLensCalibration(*msg);
  if (received_ && msg->header.frame_id == frame_id_ && sameLens(calibration, calibration_))
  {
    return;  // the same CameraInfo again (published with every frame): nothing changed
  }
  received_ = true;
  frame_id_ = msg->header.frame_id;
  calibration_ = std::move(calibration);
  check_ = projectorLens(calibration_, lens_, distortion_);
  ++lens_revision_;
  news_.raise();
}

const OffViewResult& OffViewSource::nothing(CueStatus::Level level, const std::string& why)
{
  resetCue();
  status_ = CueStatus{level, why + ": no off-view cue"};
  return empty_;
}

const OffViewResult& OffViewSource::cueAt(rviz::FrameManager& frames, const void* path_id,
                                          const std::vector<Vec2>& path, const std::vector<double>& lengths,
                                          bool robot_known, const OffViewInput& robot,
                                          const OffViewParameters& parameters)
{
  const std::string& topic = subscription_.topic();
  if (!subscription_.error().empty())
  {
    return nothing(CueStatus::Level::Error, subscription_.error());
  }
  if (topic.empty())
  {
    return nothing(CueStatus::Level::Warn, "No Projector info topic set");
  }
  if (!received_)
  {
    return nothing(CueStatus::Level::Warn, "No CameraInfo received yet on " + topic);
  }
  if (!check_.ok())
  {
    return nothing(CueStatus::Level::Error, "Unusable CameraInfo on " + topic + ": " + check_.error);
  }
  if (frame_id_.empty())
  {
    return nothing(CueStatus::Level::Error,
                   "The CameraInfo on " + topic + " has an empty frame_id (no projector pose)");
  }
  Ogre::Vector3 position;
  Ogre::Quaternion orientation;
  if (!frames.getTransform(frame_id_, ros::Time(), position, orientation))
  {
    std::string error;
    frames.transformHasProblems(frame_id_, ros::Time(), error);
    const bool expected = RosClock::shared().policy().justStartedOrJumpedBack();
    return nothing(expected ? CueStatus::Level::Warn : CueStatus::Level::Error,
                   (expected ? std::string(kWaitingForTfAfterJump) : std::string()) +
                       "No transform from the projector's frame '" + frame_id_ + "' (the CameraInfo's frame_id) " +
                       "to the fixed frame: " + error);
  }
  const std::array<double, 7> pose{position.x, position.y, position.z, orientation.x, orientation.y, orientation.z,
                                   orientation.w};
  if (pose != lit_pose_ || lens_revision_ != lit_revision_)
  {
    lit_pose_ = pose;
    lit_revision_ = lens_revision_;
    const RigidTransform optical_to_fixed = RigidTransform::fromQuaternion(
        orientation.x, orientation.y, orientation.z, orientation.w, Vec3{position.x, position.y, position.z});
    const FloorFootprint footprint(lens_, optical_to_fixed, kMaxThrow, distortion_);
    lit_complete_ = footprint.complete();
    ++lit_changes_;
    lit_.clear();
    for (const Vec3& p : footprint.outline())
    {
      lit_.push_back(Vec2{p.x, p.y});
    }
  }
  if (!lit_complete_)
  {
    return nothing(CueStatus::Level::Warn, "Part of the projector's image does not reach the floor within " +
                                               std::to_string(int(kMaxThrow)) + " m (no lit floor patch)");
  }
  if (!robot_known)
  {
    return nothing(CueStatus::Level::Warn, "No robot pose (see the Robot status)");
  }
  const Key key{path_id, path.size(), lit_changes_,
                {robot.robot.x, robot.robot.y, robot.heading, robot.start, robot.drawn_from}, parameters};
  if (key == built_)
  {
    return cue_.result();  // as last time (status_ too)
  }
  built_ = key;
  ++builds_;
  OffViewInput input = robot;
  input.lit = lit_;
  const OffViewResult& result = cue_.build(path, lengths, input, parameters);
  // A cue left out because it would cover arrows in view is the design working, not a fault.
  const bool normal = result.kind != OffViewKind::None || result.by_design;
  std::string text = result.kind == OffViewKind::None ? "Nothing drawn: " + result.reason
                                                      : std::string(toString(result.kind)) + ": " + result.reason;
  status_ = CueStatus{normal ? CueStatus::Level::Ok : CueStatus::Level::Warn, text};
  return result;
}
}  // namespace rviz_projector
