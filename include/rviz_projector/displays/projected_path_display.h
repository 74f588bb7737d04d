// rviz display "rviz_projector/ProjectedPath": evenly spaced arrows and a destination circle on the
// floor for a nav_msgs/Path. A thin adapter: PathSpacer places the arrows, FloorMesh draws them.
#pragma once

#include "rviz_projector/core/clock_policy.h"

#ifndef Q_MOC_RUN
#include <chrono>
#include <memory>
#include <vector>

#include <QTimer>
#include <nav_msgs/Path.h>
#include <ros/callback_queue.h>
#include <rviz/message_filter_display.h>

#include "rviz_projector/core/cue_drawing.h"
#include "rviz_projector/core/path_spacer.h"
#include "rviz_projector/core/path_triangles.h"
#include "rviz_projector/core/vec2.h"
#include "rviz_projector/displays/path_cue_source.h"
#include "rviz_projector/displays/path_after_jump.h"
#include "rviz_projector/displays/private_callback_queue.h"
#include "rviz_projector/displays/projection_animation.h"
#include "rviz_projector/displays/corridor_source.h"
#include "rviz_projector/displays/off_view_source.h"
#include "rviz_projector/displays/stop_zone_source.h"
#endif

namespace rviz
{
class ColorProperty;
class EnumProperty;
class FloatProperty;
}  // namespace rviz

namespace rviz_projector
{
class FloorMesh;
struct PathCueProperties;
struct CorridorProperties;
struct OffViewProperties;
struct StopZoneProperties;

/// The base of ProjectedPathDisplay: rviz's MessageFilterDisplay, destroyed before the queue.
class ProjectedPathBase : protected PrivateCallbackQueue, public rviz::MessageFilterDisplay<nav_msgs::Path>
{
};

/// Cues (issue 15: horizon, marching, robot state, pre-motion warning, turn signal; issue 25: stop
/// zone, corridor, off-view cue) are computed by
/// the core's CueDrawing from PathCueSource's inputs at the time of each frame (AnimatedDrawing).
class ProjectedPathDisplay : public ProjectedPathBase, public AnimatedDrawing
{
  Q_OBJECT
public:
  /// Default topic: the global plan of move_base's TrajectoryPlannerROS, as on the reference robot.
  static constexpr const char* kDefaultTopic = "/move_base/TrajectoryPlannerROS/global_plan";

  ProjectedPathDisplay();
  ~ProjectedPathDisplay() override;

  void reset() override;
  /// Loads the config, then reports values that were clamped or replaced (a "Config" warning).
  void load(const rviz::Config& config) override;

  /// Arrows and destination currently drawn, in the fixed frame (for tests and tools).
  const SpacedPath& spacedPath() const { return *spaced_; }
  /// Triangles in the arrow mesh and the circle mesh.
  std::size_t arrowTriangleCount() const;
  std::size_t circleTriangleCount() const;
  /// How often the meshes were rebuilt: once per new path or property change, never per frame
  /// (with an animating cue: once per frame that looks different).
  std::size_t meshBuilds() const { return mesh_builds_; }
  /// Triangles of the turn-signal glyph drawn now.
  std::size_t glyphTriangleCount() const;
  /// Triangles of the stop zone drawn now (fill and bar).
  std::size_t stopZoneTriangleCount() const;
  /// Odometry messages the stop zone took (for tests: ROS time may move on once it has its message).
  std::size_t odometryMessages() const { return stop_source_.messages(); }
  /// Triangles of the corridor drawn now (edges or band).
  std::size_t corridorTriangleCount() const;
  /// Footprint messages the corridor took.
  std::size_t footprintMessages() const { return corridor_source_.messages(); }
  std::size_t footprintTransforms() const { return corridor_source_.transforms(); }
  /// Triangles of the off-view cue drawn now.
  std::size_t offViewTriangleCount() const;
  /// The off-view cue's source (its lit area, CameraInfo messages taken).
  const OffViewSource& offViewSource() const { return off_view_source_; }

  /// Brings the cues up to `now` (ROS time); called by every projector at each frame tick and by
  /// rviz's update. Redraws only when the picture changes. No cue on: nothing.
  void advance(const ros::Time& now) override;
  void update(float wall_dt, float ros_dt) override;

protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;
  void processMessage(const nav_msgs::Path::ConstPtr& msg) override;
  /// Draws `msg` with the transform to the fixed frame at `lookup_stamp` (its own stamp, or zero:
  /// the newest, for a plan whose transform tf cleared at a backward jump of ROS time).
  void draw(const nav_msgs::Path::ConstPtr& msg, const ros::Time& lookup_stamp);
  /// Draws the last path again in the new fixed frame, once tf can transform it (rviz's base class
  /// would clear it until the planner publishes again, which a latched plan never does).
  void fixedFrameChanged() override;
  /// Reports a path whose frame cannot be transformed (yet) to the fixed frame.
  /// Sees every message before the tf filter (and whether its publisher latches).
  void checkFrame(const ros::MessageEvent<nav_msgs::Path const>& event);

private Q_SLOTS:
  /// Handles this display's own messages (its private queue), promptly and outside rviz's update.
  void drainQueue();
  void updateSpacing();
  void updateAppearance();  // colours, alpha, height, style: same arrows, new meshes
  /// Clears the drawing when the path shown arrived longer than Path timeout ago (also called by
  /// the drain timer, which runs whether or not messages arrive).
  void checkPathTimeout();
  /// A cue property changed: new settings, drawn at once.
  void updateCues();
  void updateStateTopic();
  /// A Stop zone property changed: (un)subscribes the Odometry topic, then updateCues().
  void updateStopZone();
  /// A Corridor property changed: (un)subscribes the Footprint topic, then updateCues().
  void updateCorridor();
  /// An Off-view cue property changed: (un)subscribes the Projector info topic, then updateCues().
  void updateOffView();

private:
  /// Arrows sit this much above the circle so that where they meet (Paper mode) the arrow wins.
  static constexpr double kArrowLift = 0.001;

  SpacingParameters spacingParameters() const;
  /// Re-spaces the last path (fixed-frame points) and rebuilds the meshes.
  void rebuild();
  void redraw();
  void checkGeometry(const SpacingParameters& parameters);
  /// Any cue on (or a State topic set): the drawing comes from CueDrawing, at each frame's time.
  bool cuesActive() const;
  /// The warnings for spacing options that do not combine, each under its own status: Marching in
  /// Paper mode or with Speed-coded spacing ("Marching"), Speed-coded spacing in Paper mode
  /// ("Speed-coded spacing").
  void checkSpacingCombinations();
  /// ROS time now, from the clock every display shares (RosClock): the cue timelines' time.
  static ros::Time cueTime();
  /// Draws the cues for `now`; `force`: upload even if the picture looks the same (new colours).
  void drawCues(const ros::Time& now, bool force);
  void showCueStatus(const QString& name, const CueStatus& status, CueStatus& shown);

  rviz::EnumProperty* mode_property_;
  rviz::FloatProperty* spacing_property_;
  rviz::FloatProperty* shaft_length_property_;
  rviz::FloatProperty* shaft_diameter_property_;
  rviz::FloatProperty* head_length_property_;
  rviz::FloatProperty* head_diameter_property_;
  rviz::FloatProperty* circle_diameter_property_;
  rviz::ColorProperty* arrow_color_property_;
  rviz::ColorProperty* circle_color_property_;
  rviz::FloatProperty* alpha_property_;
  rviz::FloatProperty* height_property_;
  rviz::EnumProperty* style_property_;
  rviz::FloatProperty* path_timeout_property_;

  // Paths arrive on a queue of this display's own (the PrivateCallbackQueue base), drained every
  // few milliseconds while enabled: a new plan reaches the projector without waiting for rviz's next
  // main-view frame, and nobody spins rviz's global queue from inside a display.
  EpochWatch epoch_;  ///< of RosClock::shared(): a backward jump of ROS time forgets the old state
  PathSpacer spacer_;
  const SpacedPath* spaced_;
  SpacedPath empty_;
  std::vector<Vec2> floor_points_;  // last path, in the fixed frame
  nav_msgs::Path::ConstPtr last_msg_;  // last path drawn (null: none yet); floor_points_ hold it
  bool latched_publisher_ = false;  ///< the last path came from a latched publisher (Reset subscribes again)
  std::chrono::steady_clock::time_point last_arrival_;  // when last_msg_ arrived (steady wall clock)
  /// A path whose transform is not there yet waits in the tf filter: a warning, an error once it
  /// has waited kTfWaitGrace (a path a moment ahead of its tf is normal: topics race, bags replay
  /// them in the order they were recorded).
  static constexpr double kTfWaitGrace = 1.0;
  bool tf_waiting_ = false;
  PathAfterJump after_jump_;  ///< the plan received last: not lost when ROS time jumps back
  std::chrono::steady_clock::time_point tf_wait_since_;
  QString tf_wait_error_;
  std::size_t dropped_poses_ = 0;
  PathTriangles triangles_;  // buffers kept between paths
  std::size_t mesh_builds_ = 0;
  std::unique_ptr<FloorMesh> arrow_mesh_;
  std::unique_ptr<FloorMesh> circle_mesh_;

  std::unique_ptr<PathCueProperties> cue_properties_;
  PathCueSettings cue_settings_;
  PathCueSource cue_source_;
  CueDrawing cue_next_;   // built for this frame
  CueDrawing cue_drawn_;  // on the meshes (swapped with cue_next_: no allocation)
  GoalCueFrame::Colour cue_colour_drawn_ = GoalCueFrame::Colour::Normal;
  double spaced_phase_ = 0.0;       // marching phase spaced_ was computed with
  double coded_speed_ = 0.0;        // Speed-coded spacing: the speed (cm/s steps) spaced_ was computed with
  ros::Time last_advance_;
  CueStatus robot_status_shown_;
  CueStatus state_status_shown_;
  std::unique_ptr<FloorMesh> glyph_mesh_;

  std::unique_ptr<StopZoneProperties> stop_properties_;
  StopZoneSource stop_source_;
  CueStatus stop_status_shown_;
  std::unique_ptr<FloorMesh> stop_mesh_;

  std::unique_ptr<CorridorProperties> corridor_properties_;
  CorridorSource corridor_source_;
  CorridorFootprint corridor_typed_;  ///< from the Radius or Polygon property (updateCorridor)
  CueStatus corridor_status_shown_;
  std::unique_ptr<FloorMesh> corridor_mesh_;
  /// The footprint for this frame into cue_settings_, its status shown.
  void takeCorridorFootprint();

  std::unique_ptr<OffViewProperties> off_view_properties_;
  OffViewSource off_view_source_;
  CueStatus off_view_status_shown_;
  std::vector<Vec2> off_view_next_;   ///< the cue's triangles for this frame (empty: none)
  std::vector<Vec2> off_view_drawn_;  ///< on off_view_mesh_ (swapped with off_view_next_)
  std::unique_ptr<FloorMesh> off_view_mesh_;
  /// The off-view cue for this frame into off_view_next_, its status shown (group off: nothing).
  void buildOffView(const PathCueInput& input);
};
}  // namespace rviz_projector
