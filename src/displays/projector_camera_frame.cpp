// ProjectorCameraDisplay, frame by frame (the other half, projector_camera_display.cpp: lifecycle,
// properties, subscriptions, statuses). The frame clock ticks onFrameTimer(): the pipeline takes
// the CameraInfo that arrived and this frame's clock reading; animated drawings advance; renderNow()
// asks the pipeline for the pose (prepareFrame), updates the overlay and crosshairs, and renders
// only when the ProjectionGate says the projector would show something new.
#include <algorithm>
#include <chrono>
#include <string>

#include <OgreViewport.h>

#include <rviz/display_context.h>
#include <rviz/properties/display_group_visibility_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/string_property.h>

#include "rviz_projector/displays/distortion_warp.h"
#include "rviz_projector/displays/projection_animation.h"
#include "rviz_projector/displays/projection_change_counter.h"
#include "rviz_projector/displays/projection_gate.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_crosshairs.h"
#include "rviz_projector/displays/projector_floor_overlay.h"
#include "rviz_projector/displays/projector_image_publisher.h"
#include "rviz_projector/displays/projector_output.h"
#include "rviz_projector/displays/projector_pattern.h"
#include "rviz_projector/displays/projector_view.h"
#include "rviz_projector/displays/ros_clock.h"
#include "rviz_projector/displays/viewport_clear.h"

namespace rviz_projector
{
bool ProjectorCameraDisplay::updateCrosshairs()
{
  const bool wanted = props_.testPattern() == TestPattern::Crosshairs && hasLens();
  std::string problem;
  if (wanted && crosshairs_->update(lens().width(), lens().height(), props_.crosshair_rows->getInt(),
                                    props_.crosshair_cols->getInt(), problem))
  {
    markChanged();
  }
  warnIf(QStringLiteral("Test pattern"), problem.empty() ? QString() : "No crosshairs: " + QString::fromStdString(problem));
  return wanted;
}

void ProjectorCameraDisplay::pollPattern()
{
  if (pattern_->poll(hasLens() ? lens().width() : 0, hasLens() ? lens().height() : 0,
                     props_.pattern_timeout->getFloat(), std::chrono::steady_clock::now()))
  {
    markChanged();
    pattern_changed_ = true;
  }
  showPatternStatus();
}

void ProjectorCameraDisplay::showPatternStatus()
{
  if (pattern_->takeStatusChange())
  {
    const QString text = QString::fromStdString(pattern_->statusText());
    switch (pattern_->level())
    {
      case ProjectorPattern::Level::None:
        deleteStatus(QStringLiteral("Pattern"));
        break;
      case ProjectorPattern::Level::Ok:
        setStatus(rviz::StatusProperty::Ok, QStringLiteral("Pattern"), text);
        break;
      case ProjectorPattern::Level::Warn:
        setStatus(rviz::StatusProperty::Warn, QStringLiteral("Pattern"), text);
        break;
      case ProjectorPattern::Level::Error:
        setStatus(rviz::StatusProperty::Error, QStringLiteral("Pattern"), text);
        break;
    }
  }
}

bool ProjectorCameraDisplay::updateCameraPose()
{
  if (fixed_frame_ != fixed_frame_shown_)  // no string conversion per frame
  {
    fixed_frame_shown_ = fixed_frame_;
    fixed_frame_std_ = fixed_frame_.toStdString();
  }
  PoseInput in;
  in.tf = context_->getTF2BufferPtr().get();
  in.fixed_frame = &fixed_frame_std_;
  in.motion = MotionSettings{props_.motion_enabled->getBool(), props_.inputLag(), props_.maxPrediction()};
  in.tf_timeout = props_.tf_timeout->getFloat();
  in.steady_now = frame_clock_.now();
  in.period = frame_clock_.period();
  const PoseStep step = pipeline_.followPose(in, RosClock::shared().policy());  // read by onFrameTimer
  if (step.transform_status_gone)
  {
    deleteStatus(QStringLiteral("Transform"));
  }
  if (step.transform_status_changed)  // a stale pose blanks the projector as a missing one does
  {
    setStatus(step.ok                            ? rviz::StatusProperty::Ok
              : step.transform_problem_expected ? rviz::StatusProperty::Warn
                                                : rviz::StatusProperty::Error,
              QStringLiteral("Transform"),
              step.ok ? QStringLiteral("OK") : QString::fromStdString(step.transform_problem));
  }
  if (step.ok)
  {
    view_->setPose(step.pose);
    showMotion(step.motion);
    showCeiling();
  }
  return step.ok;
}

void ProjectorCameraDisplay::showMotion(const MotionReport& report)
{
  if (report.status_changed)
  {
    setStatus(report.level == MotionReport::Warn ? rviz::StatusProperty::Warn : rviz::StatusProperty::Ok,
              QStringLiteral("Motion compensation"), QString::fromStdString(report.status));
  }
  if (report.line_changed)
  {
    props_.motion_state->setStdString(report.line);
  }
}

void ProjectorCameraDisplay::updateFootprint()
{
  if (!hasLens() || !pipeline_.poseOk())
  {
    overlay_->setFootprintVisible(false);
    return;
  }
  const FloorOverlayResult lit =
      overlay_->update(lens(), pipeline_.lensSource().distortion(), pipeline_.poseFollower().pose().optical_to_fixed,
                       own_changes_, props_.footprint->getBool(), props_.testPattern() == TestPattern::MetricGrid);
  updateFootprintVisible();
  own_changes_ += lit.grid_changed ? 1 : 0;  // the grid is drawn anew
  if (lit.status_changed)
  {
    setStatus(lit.complete ? rviz::StatusProperty::Ok : rviz::StatusProperty::Warn, "Footprint",
              QString::fromStdString(footprintStatusText(lit)));
  }
}

bool ProjectorCameraDisplay::prepareFrame()
{
  if (!output_ || !output_->viewport())
  {
    return false;
  }
  updateCameraPose();  // pipeline_.poseOk(): false without a lens (its Transform status goes)
  updateFootprint();
  crosshairs_shown_ = updateCrosshairs();
  if (output_->fitViewport(hasLens() ? lens().width() : 0, hasLens() ? lens().height() : 0))
  {
    warnIf(QStringLiteral("Scaling"), hasLens() ? output_->scalingNote(lens().width(), lens().height()) : QString());
  }
  return true;
}

void ProjectorCameraDisplay::updateVisibilityBits()
{
  if (visibility_property_)
  {
    visibility_property_->update();
  }
}

void ProjectorCameraDisplay::preRenderTargetUpdate(const Ogre::RenderTargetEvent& /*event*/)
{
  // rviz's camera display does the same: other camera-like displays change the displays' bits.
  updateVisibilityBits();
  // The frustum never shows in the projector's own view.
  overlay_->setFootprintVisibilityFlags(~vis_bit_);
  // A pattern, then the crosshairs: their cameras see only them (nothing else is in their scenes),
  // with or without a pose. Through a distorting lens the window shows the warp of the ideal render
  // (patterns and crosshairs are drawn at raw pixels: never warped).
  const bool image_space = pattern_->shown() || crosshairs_shown_;
  const bool warped = !image_space && warp_->active();
  Ogre::Camera* camera = pattern_->shown() ? pattern_->camera()
                         : crosshairs_shown_ ? crosshairs_->camera()
                         : warped          ? warp_->warpCamera()
                                           : view_->camera();
  const bool drawable = hasLens() && pipeline_.poseOk();
  // The warp's whole mesh covers every pixel of the viewport (its outer vertices lie on the
  // viewport's edges) and tests no depth: clearing the window before it only cost a pass over its
  // colour and depth (and ~200 KB of the GL driver's allocations per frame, scripts/bench --alloc).
  // Only its occupied cells (software renderer) leave the rest to the clear, of the colour alone:
  // the window's depth is not used under the warp. Without a pose the mesh is hidden and the clear
  // blanks the window. The scene itself (no warp) needs colour, depth and stencil.
  const bool mesh_covers = warped && drawable && warp_->coversWindow();
  const unsigned clear = !warped ? kProjectorClearBuffers : mesh_covers ? 0u : kWarpCellsClearBuffers;
  if (Ogre::Viewport* viewport = output_->viewport())
  {
    if (viewport->getCamera() != camera)
    {
      viewport->setCamera(camera);
    }
    setClearedBuffers(*viewport, clear);
  }
  warp_->setVisibilityMask(drawable ? vis_bit_ : 0u);
  output_->setVisibilityMask(image_space ? ~0u : !drawable ? 0u : warped ? ~0u : vis_bit_);
}

void ProjectorCameraDisplay::onFrameTimer()
{
  if (!isEnabled())
  {
    return;
  }
  // Only this display's own CameraInfo subscription: never rviz's global queue.
  // An unchanged CameraInfo (camera drivers repeat it with every frame) changes nothing.
  const LensEvent lens_event = pipeline_.pollLens();
  if (lens_event.any())
  {
    onLensChanged(lens_event);
  }
  pollPattern();  // after the lens: a pattern must have the lens's size
  // One reading of the clock for this frame (ROS time, its rate, a backward jump: the pipeline
  // forgot every pose and prediction of before it).
  const ClockPolicy& clock = RosClock::shared().tick();
  if (pipeline_.followClock(clock))
  {
    markChanged();
  }
  // Animated drawings (marching arrows, blinking cues) for this frame's time; each bumps the change
  // counter only when its picture changes.
  ProjectionAnimation::advanceAll(ros::Time(std::max(0.0, clock.rosNow())));
  renderNow();
  frame_clock_.frameDone(frames_rendered_, isEnabled());
}

void ProjectorCameraDisplay::onSceneChanged()
{
  if (isEnabled())
  {
    frame_clock_.requestEarlyFrame();  // unless a frame went out less than a period ago
  }
}

void ProjectorCameraDisplay::renderNow()
{
  if (!isEnabled() || !output_ || !output_->isShown() || !prepareFrame())
  {
    return;
  }
  // A new pattern goes out on the Image output at once (a camera simulated from it sees it then).
  const bool publish = hasLens() && (image_publisher_->due() || (pattern_changed_ && image_publisher_->active()));
  FrameState state;
  state.pose = view_->poseKey();
  state.changes = ProjectionChangeCounter::value() + own_changes_;
  state.visibility = gate_->visibilitySignature();
  state.image = output_->imageRect();
  state.drawable = hasLens() && (pipeline_.poseOk() || crosshairs_shown_ || pattern_->shown());
  if (output_->takeRepaintRequest())
  {
    gate_->invalidate();  // exposed again: the window's content must be drawn anew
  }
  // A pattern is only ever shown pixel for pixel: a window that scales the image (another screen
  // size, not full screen) refuses it rather than light the floor where no solver expects.
  if (pattern_->shown() && (state.image.width != int(lens().width()) || state.image.height != int(lens().height())))
  {
    pattern_->refuse("Not shown: the output window shows the " + std::to_string(lens().width()) + "x" +
                     std::to_string(lens().height()) + " image as " + std::to_string(state.image.width) + "x" +
                     std::to_string(state.image.height) +
                     " (scaled): a pattern is shown 1:1 only (a screen of the projector's resolution, Full screen on)");
    showPatternStatus();
    markChanged();
    state.changes = ProjectionChangeCounter::value() + own_changes_;
    state.drawable = hasLens() && (pipeline_.poseOk() || crosshairs_shown_);
  }
  if (!gate_->needsFrame(state) && !publish)
  {
    ++frames_skipped_;  // the projector already shows exactly this
    pattern_->frameShown();  // e.g. a 0 x 0 image while the scene was already shown: acknowledged
    return;
  }
  if (!crosshairs_shown_ && !pattern_->shown())
  {
    warp_->renderIdeal();  // through a distorting lens: the ideal view first (nothing without one)
    if (warp_->active() && warp_->readsDirectly() != warp_status_direct_)
    {
      showWarpStatus();  // the direct read failed this frame: the status says so from now on
    }
  }
  output_->render(!publish);
  ++frames_rendered_;
  if (publish)
  {
    // Stamped with the time of the pose it was drawn from (the prediction's target when predicted).
    image_publisher_->publish(output_->renderWindow(), output_->imageRect(), lens(),
                              pipeline_.lensSource().distortion(), projectorFrame(),
                              pipeline_.imageStamp(ros::Time::now()));
    output_->swap();
  }
  pattern_changed_ = false;
  pattern_->frameShown();  // "/shown": the pattern (or the scene after it) went to the screen
  pipeline_.frameShown(frame_clock_.now(), frame_clock_.period());  // the render delay, measured
}

void ProjectorCameraDisplay::showCeiling()
{
  const ProjectorView::Ceiling ceiling = view_->ceiling();
  if (static_cast<int>(ceiling) == ceiling_shown_)
  {
    return;
  }
  ceiling_shown_ = static_cast<int>(ceiling);
  const float height = props_.max_lit_height->getFloat();
  switch (ceiling)
  {
    case ProjectorView::Ceiling::Off:
    case ProjectorView::Ceiling::NoLens:
      deleteStatus("Max lit height");
      break;
    case ProjectorView::Ceiling::Clipping:
      setStatus(rviz::StatusProperty::Ok, "Max lit height",
                QString("Nothing of the scene above %1 m is drawn (only what rviz's scene holds)").arg(height));
      break;
    case ProjectorView::Ceiling::ProjectorBelow:
      setStatus(rviz::StatusProperty::Warn, "Max lit height",
                QString("The projector is not above %1 m: nothing is clipped").arg(height));
      break;
  }
}
}  // namespace rviz_projector
