// rviz display "rviz_projector/ProjectorCamera": renders the scene through the projector's lens
// (CameraInfo) from its pose (tf) straight into a full-screen window on the projector's screen.
// An orchestrator: it owns the properties and statuses and wires the parts together.
//   ProjectorPipeline          the per-frame inputs without rviz: lens (ProjectorLensSource), projector
//                              frame, clock (ClockPolicy), pose (ProjectorPoseFollower), motion
//                              compensation (ProjectorMotion); explicit events and resets
//   ProjectorView              the OGRE camera at the projector's pose, through its lens
//   ProjectorOutput            output window, render window, viewport, screens, exact letterbox
//   ProjectionGate             whether a frame is needed; Visibility ticks by display identity
//   ProjectorImagePublisher    optional Image + matching CameraInfo
//   ProjectorFloorOverlay      frustum and lit area in rviz's main view, test grid on the floor
//   ProjectorCrosshairs        the calibration crosshairs, in image space (Test pattern)
//   ProjectorPattern           the Pattern topic: an image shown 1:1 instead of the scene, acknowledged
//   ProjectorFrameClock        when to render: FramePacer (core) deadlines at the Frame rate limit /
//                              screen refresh, early frames on changes, FrameRateMeter (core)
//   StatusCache                the statuses shown: only changes reach rviz
//   ProjectorCameraProperties  the properties, and the output window they ask for
//   health() (projector_camera_health.cpp)  what the display does, in plain numbers
// doc/dev/architecture.md says how one frame flows.
#pragma once

#ifndef Q_MOC_RUN
#include <array>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <OgreRenderTargetListener.h>
#include <ros/ros.h>
#include <rviz/display.h>
#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/screen_choice.h"
#include "rviz_projector/displays/projector_camera_health.h"
#include "rviz_projector/displays/projector_camera_properties.h"
#include "rviz_projector/displays/projector_frame_clock.h"
#include "rviz_projector/displays/projector_pipeline.h"
#include "rviz_projector/displays/status_cache.h"
#endif


namespace rviz
{
class DisplayGroupVisibilityProperty;
}  // namespace rviz

namespace rviz_projector
{
class DistortionWarp;
class ProjectionGate;
class ProjectorCrosshairs;
class ProjectorFloorOverlay;
class ProjectorImagePublisher;
class ProjectorOutput;
class ProjectorOutputWindow;
class ProjectorPattern;
class ProjectorView;

class ProjectorCameraDisplay : public rviz::Display, public Ogre::RenderTargetListener
{
  Q_OBJECT
public:
  static constexpr const char* kDefaultTopic = "/projector/camera_info";
  static constexpr const char* kAutomaticScreen = rviz_projector::kAutomaticScreen;

  ProjectorCameraDisplay();
  ~ProjectorCameraDisplay() override;

  /// rviz's Reset: statuses are cleared, then every problem that still holds is raised again.
  void reset() override;
  /// Loads the config, then reports values that were clamped or replaced (a "Config" warning).
  void load(const rviz::Config& config) override;
  void setTopic(const QString& topic, const QString& datatype) override;
  /// Statuses are evaluated every frame; these forward only actual changes to rviz (StatusCache:
  /// each rviz call posts an event and repaints the Displays panel).
  void setStatus(rviz::StatusProperty::Level level, const QString& name, const QString& text) override;
  void deleteStatus(const QString& name) override;
  void clearStatuses() override;

  /// Frames skipped because nothing the projector shows had changed.
  std::uint64_t framesSkipped() const { return frames_skipped_; }
  /// Frames rendered into the output window so far.
  std::uint64_t framesRendered() const { return frames_rendered_; }
  /// CameraInfo messages handled since the topic was (re)subscribed, changed or not.
  std::uint64_t cameraInfoMessages() const { return pipeline_.lensSource().messagesReceived(); }
  /// The output window (nullptr while none exists).
  ProjectorOutputWindow* outputWindow() const;
  /// The lens in use; valid only when hasLens().
  const PinholeModel& lens() const { return pipeline_.lens(); }
  bool hasLens() const { return pipeline_.hasLens(); }
  /// The visibility bit used by the projector view (0 when none could be allocated).
  std::uint32_t visibilityBit() const { return vis_bit_; }
  /// Sets the displays' visibility bits from the Visibility ticks now (rviz applies them when the
  /// property updates: before each of this view's renders, so not yet right after a config load).
  void updateVisibilityBits();
  /// What the display is doing now (frame rate, data ages, blanking, window), for diagnostics.
  ProjectorCameraHealth health() const;
  /// Motion compensation: the last prediction and the time it was made for.
  const ProjectorMotion& motion() const { return pipeline_.motion(); }

protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;
  void fixedFrameChanged() override;

  // Ogre::RenderTargetListener
  void preRenderTargetUpdate(const Ogre::RenderTargetEvent& event) override;

public Q_SLOTS:
  /// Renders the projector view now if anything it shows changed (the frame timer calls this).
  void renderNow();

private Q_SLOTS:
  void onFrameTimer();
  /// A display of this package changed (ProjectionChangeNotifier): frame now if the rate allows.
  void onSceneChanged();
  void resubscribe();
  /// Shows the output window as the properties ask (when enabled): "Output" status.
  void updateOutput();
  /// Lens, clipping and background into the projector view (no other effect).
  void applyProjection();
  /// The Frame property changed.
  void onFramePropertyChanged();
  /// Max lit height changed: the projector view's clipping plane.
  void updateMaxLitHeight();
  void updateFrameRate();
  void onFootprintPropertyChanged();
  void updateTestPattern();
  void updateImageOutput();
  void fillScreenOptions();
  /// Subscribes to the Motion compensation's Odometry topic (when enabled).
  void updateMotionOdometry();
  /// The Pattern topic changed (or the display was enabled/disabled): (un)subscribes it.
  void updatePatternTopic();

private:
  void subscribe();
  void unsubscribe();
  /// A CameraInfo changed the lens and/or the frame (or was forgotten): statuses, projection,
  /// window size; a new projector frame resets the motion history, a new lens does not.
  void onLensChanged(const LensEvent& event);
  /// The CameraInfo, Distortion and Field of view statuses, as the lens source says.
  void showLensStatuses();
  /// The distortion warp for the lens (none: released) and its "Distortion" status.
  void updateWarp();
  /// The "Distortion" status of a warp that is drawn (which cells, how the render is read back).
  void showWarpStatus();
  /// "Main view" warning when rviz's own view is known to starve this one (main_view_cost.h).
  void checkMainViewCost();
  /// The "Visibility" error when no visibility bit was left for this display.
  void showVisibilityStatus();
  /// Moves the camera to the projector's pose (latest tf, moved by motion compensation); false
  /// (with a status) when unavailable.
  bool updateCameraPose();
  /// The Motion compensation status and Prediction line, as motion_ reported them.
  void showMotion(const MotionReport& report);
  void updateFootprint();
  /// Follows the lens and Rows/Columns; true while the projector shows the crosshairs.
  bool updateCrosshairs();
  /// The Pattern topic's arrivals and timeout, and its "Pattern" status (onFrameTimer).
  void pollPattern();
  /// The "Pattern" status as ProjectorPattern says, when it changed.
  void showPatternStatus();
  /// Follows tf, the lens and the window; false when there is no window to draw into.
  bool prepareFrame();
  void updateFootprintVisible();
  /// Something this display itself draws or how it draws changed: render again.
  void markChanged() { ++own_changes_; }
  /// The Max lit height status, when the view's ceiling state changed (cheap: called every frame).
  void showCeiling();
  /// The Frame property, or the CameraInfo's frame_id when it is empty.
  const std::string& projectorFrame() const { return pipeline_.projectorFrame(); }
  /// A Warn status `name` with this text; deleted when the text is empty.
  void warnIf(const QString& name, const QString& warning);
  /// The parts' Ok/Warn/Error levels are rviz's, value for value.
  template <typename Level>
  static rviz::StatusProperty::Level statusLevel(Level level)
  {
    static_assert(int(Level::Ok) == rviz::StatusProperty::Ok && int(Level::Warn) == rviz::StatusProperty::Warn &&
                      int(Level::Error) == rviz::StatusProperty::Error,
                  "status levels differ");
    return static_cast<rviz::StatusProperty::Level>(level);
  }

  ProjectorCameraProperties props_;
  rviz::DisplayGroupVisibilityProperty* visibility_property_ = nullptr;

  ProjectorPipeline pipeline_;  ///< lens, projector frame, clock, pose and motion: the per-frame inputs
  std::pair<std::uint32_t, std::uint32_t> shown_size_{0, 0};  ///< image size the window was laid out for
  QString fixed_frame_shown_;    ///< the fixed frame fixed_frame_std_ was made from
  std::string fixed_frame_std_;

  std::unique_ptr<ProjectionGate> gate_;
  std::unique_ptr<ProjectorOutput> output_;
  std::unique_ptr<ProjectorImagePublisher> image_publisher_;
  std::unique_ptr<ProjectorView> view_;
  std::uint32_t vis_bit_ = 0;
  ProjectorFrameClock frame_clock_;
  std::uint64_t frames_rendered_ = 0;
  std::uint64_t frames_skipped_ = 0;
  std::uint64_t own_changes_ = 0;
  int ceiling_shown_ = -1;  // ProjectorView::Ceiling of the Max lit height status shown (-1: none yet)
  StatusCache statuses_;
  std::unique_ptr<ProjectorFloorOverlay> overlay_;
  std::unique_ptr<ProjectorCrosshairs> crosshairs_;
  bool crosshairs_shown_ = false;
  bool warp_status_direct_ = false;  // the Distortion status says the render is read back directly
  std::unique_ptr<ProjectorPattern> pattern_;  ///< the Pattern topic (a pattern replaces the scene)
  bool pattern_changed_ = false;               ///< a new pattern since the last frame: publish it at once
  std::unique_ptr<DistortionWarp> warp_;  ///< drawing through the lens's D (inactive without one)
};
}  // namespace rviz_projector
