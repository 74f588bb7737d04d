#include "rviz_projector/displays/projector_camera_display.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <OgreRenderWindow.h>
#include <OgreViewport.h>
#include <QGuiApplication>
#include <QScreen>

#include <rviz/bit_allocator.h>
#include <rviz/display_context.h>
#include <rviz/display_group.h>
#include <rviz/load_resource.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/display_group_visibility_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/string_property.h>
#include <rviz/window_manager_interface.h>

#include "rviz_projector/displays/main_view_cost.h"
#include "rviz_projector/displays/projection_change_counter.h"
#include "rviz_projector/displays/projection_animation.h"
#include "rviz_projector/displays/projection_change_notifier.h"
#include "rviz_projector/displays/projection_gate.h"
#include "rviz_projector/displays/projector_crosshairs.h"
#include "rviz_projector/displays/projector_floor_overlay.h"
#include "rviz_projector/displays/projector_image_publisher.h"
#include "rviz_projector/displays/projector_lens_source.h"
#include "rviz_projector/displays/distortion_warp.h"
#include "rviz_projector/displays/projector_output.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_projector/displays/projector_pattern.h"
#include "rviz_projector/displays/projector_pose.h"
#include "rviz_projector/displays/projector_view.h"
#include "rviz_projector/displays/ros_clock.h"

namespace rviz_projector
{
ProjectorCameraDisplay::ProjectorCameraDisplay() : props_(this)
{
}

ProjectorCameraDisplay::~ProjectorCameraDisplay()
{
  frame_clock_.stop();
  unsubscribe();
  image_publisher_.reset();
  output_.reset();  // listener, viewport, render window, widget
  pattern_.reset();  // its camera was the viewport's while a pattern was shown
  warp_.reset();    // its texture's viewport uses the view's camera
  gate_.reset();
  overlay_.reset();
  crosshairs_.reset();
  view_.reset();
  if (vis_bit_ != 0)
  {
    context_->visibilityBits()->freeBits(vis_bit_);
  }
}

void ProjectorCameraDisplay::onInitialize()
{
  view_ = std::make_unique<ProjectorView>(scene_manager_);
  view_->setMaxLitHeight(props_.max_lit_height->getFloat());

  // The gate first: it must hear a display's removal before the Visibility property forgets it.
  gate_ = std::make_unique<ProjectionGate>(context_->getRootDisplayGroup(), this);
  vis_bit_ = context_->visibilityBits()->allocBit();
  visibility_property_ = new rviz::DisplayGroupVisibilityProperty(
      vis_bit_, context_->getRootDisplayGroup(), this, "Visibility", true,
      "Displays shown in the projector view. New displays start hidden, except this package's path "
      "displays (ProjectedPath, ProjectionMask).");
  visibility_property_->setIcon(rviz::loadPixmap("package://rviz/icons/visibility.svg", true));
  addChild(visibility_property_, 0);
  // Defaults for the displays that exist now (a loaded config overrides them afterwards) and for
  // every display added later.
  gate_->attach(visibility_property_);

  output_ = std::make_unique<ProjectorOutput>("Projector: " + getName(), view_->camera(), this);
  // Esc leaves full screen; closing the window disables the display (both after the window's
  // handlers returned).
  connect(output_.get(), &ProjectorOutput::leaveFullScreenRequested, this,
          [this] { props_.full_screen->setBool(false); });
  connect(output_.get(), &ProjectorOutput::closedByUser, this, [this] { setEnabled(false); });
  image_publisher_ = std::make_unique<ProjectorImagePublisher>();
  overlay_ = std::make_unique<ProjectorFloorOverlay>(scene_manager_, scene_node_);
  crosshairs_ = std::make_unique<ProjectorCrosshairs>();
  pattern_ = std::make_unique<ProjectorPattern>();
  warp_ = std::make_unique<DistortionWarp>(view_->camera(), this);

  connect(qApp, SIGNAL(screenAdded(QScreen*)), this, SLOT(updateOutput()));  // when enabled
  connect(qApp, SIGNAL(screenRemoved(QScreen*)), this, SLOT(updateOutput()));
  connect(&frame_clock_, &ProjectorFrameClock::tick, this, &ProjectorCameraDisplay::onFrameTimer);
  connect(&ProjectionChangeNotifier::instance(), &ProjectionChangeNotifier::changed, this,
          &ProjectorCameraDisplay::onSceneChanged, Qt::QueuedConnection);
  updateFrameRate();
  pipeline_.setFrameProperty(props_.frame->getStdString());
  applyProjection();
  showVisibilityStatus();
  showLensStatuses();
}

void ProjectorCameraDisplay::showVisibilityStatus()
{
  if (vis_bit_ == 0)
  {
    setStatus(rviz::StatusProperty::Error, "Visibility",
              "All 32 visibility bits are in use (too many camera displays): the projector view stays empty");
  }
}

void ProjectorCameraDisplay::onEnable()
{
  checkMainViewCost();
  pipeline_.reset();
  subscribe();
  updateOutput();
  frame_clock_.start();
}

void ProjectorCameraDisplay::onDisable()
{
  frame_clock_.stop();
  unsubscribe();
  if (output_)
  {
    output_->hide();
  }
  overlay_->setFootprintVisible(false);
}

void ProjectorCameraDisplay::checkMainViewCost()
{
  const std::string warning = mainViewCostWarning(*context_);
  warnIf("Main view", QString::fromStdString(warning));
}

void ProjectorCameraDisplay::reset()
{
  Display::reset();  // clears every status
  if (!output_)
  {
    return;  // not initialised
  }
  // rviz resets its displays when ROS time jumps backwards (a bag loop): nothing of before is kept,
  // and every problem that still holds is raised again, at once.
  pipeline_.reset();
  overlay_->invalidate();
  ceiling_shown_ = -1;
  showCeiling();
  showVisibilityStatus();
  checkMainViewCost();
  showLensStatuses();
  applyProjection();
  updateImageOutput();
  gate_->invalidate();
  if (isEnabled())
  {
    updateOutput();
    prepareFrame();
    // A projector's CameraInfo is usually published once, latched: subscribe again to get it back
    // (the lens in use stays until a new one arrives).
    unsubscribe();
    subscribe();
  }
}

void ProjectorCameraDisplay::load(const rviz::Config& config)
{
  Display::load(config);
  const QString replaced = props_.checkLoaded(config);
  const std::string wanted = props_.normaliseScreen();  // labels of older configs: plain names
  // An output screen that is not connected is said at once, even while the display is disabled
  // (placing the window, when enabled, keeps the status up to date).
  if (!isEnabled() && wanted != kAutomaticScreen && !ProjectorOutput::screenConnected(wanted))
  {
    setStatus(rviz::StatusProperty::Warn, "Output",
              QString("Screen '%1' is not connected").arg(QString::fromStdString(wanted)));
  }
  warnIf("Config", replaced.isEmpty() ? replaced : "Unusable values in the config replaced: " + replaced);
}

void ProjectorCameraDisplay::fixedFrameChanged()
{
  updateTestPattern();
}

void ProjectorCameraDisplay::setTopic(const QString& topic, const QString& /*datatype*/)
{
  props_.topic->setString(topic);
}

void ProjectorCameraDisplay::resubscribe()
{
  unsubscribe();
  onLensChanged(pipeline_.forgetLens());
  subscribe();
}

void ProjectorCameraDisplay::subscribe()
{
  if (!isEnabled() || props_.topic->getTopicStd().empty())
  {
    return;
  }
  const std::string error = pipeline_.subscribeLens(props_.topic->getTopicStd());
  setStatus(error.empty() ? rviz::StatusProperty::Ok : rviz::StatusProperty::Error, "Topic",
            error.empty() ? QString("OK") : "Error subscribing: " + QString::fromStdString(error));
  updateMotionOdometry();
  updatePatternTopic();
}

void ProjectorCameraDisplay::unsubscribe()
{
  pipeline_.unsubscribeLens();
  pipeline_.setOdometryTopic(std::string());
  if (pattern_)
  {
    pattern_->unsubscribe();
    showPatternStatus();
  }
}

void ProjectorCameraDisplay::updatePatternTopic()
{
  if (!pattern_)
  {
    return;
  }
  markChanged();  // a pattern shown goes
  pattern_->subscribe(isEnabled() ? props_.pattern_topic->getTopicStd() : std::string());
  showPatternStatus();  // ProjectorPattern owns the status, an error subscribing included
}

void ProjectorCameraDisplay::updateMotionOdometry()
{
  const std::string error = pipeline_.setOdometryTopic(isEnabled() ? props_.motion_odometry->getTopicStd() : std::string());
  warnIf("Odometry topic", error.empty() ? QString() : "Error subscribing: " + QString::fromStdString(error));
}

void ProjectorCameraDisplay::showLensStatuses()
{
  const LensStatuses s = pipeline_.lensSource().statuses(props_.topic->getTopic());
  setStatus(statusLevel(s.camera_info_level), "CameraInfo", s.camera_info);
  for (const auto& warning : {std::make_pair(QString("Distortion"), s.distortion),
                              std::make_pair(QString("Field of view"), s.field_of_view)})
  {
    warnIf(warning.first, warning.second);
  }
}

void ProjectorCameraDisplay::onLensChanged(const LensEvent& event)
{
  markChanged();  // a new frame_id: the pipeline restarted the motion history
  if (!event.lens)
  {
    return;  // a new frame_id only: the same lens, window and statuses
  }
  showLensStatuses();
  const bool size_changed = hasLens() != (shown_size_.first > 0) ||
                            (hasLens() && (lens().width() != shown_size_.first || lens().height() != shown_size_.second));
  shown_size_ = hasLens() ? std::make_pair(lens().width(), lens().height()) : std::make_pair(0u, 0u);
  updateWarp();
  applyProjection();
  if (size_changed && isEnabled())
  {
    updateOutput();
  }
}

void ProjectorCameraDisplay::onFramePropertyChanged()
{
  markChanged();
  pipeline_.setFrameProperty(props_.frame->getStdString());  // a new frame restarts the motion history
  context_->queueRender();  // the frustum in the main view
}

void ProjectorCameraDisplay::applyProjection()
{
  markChanged();
  if (!view_)
  {
    return;
  }
  // Through a distorting lens the scene is rendered as the warp's ideal pinhole, then warped.
  const PinholeModel* projection = !hasLens() ? nullptr : warp_ && warp_->active() ? &warp_->idealLens() : &lens();
  const std::string clip = view_->setProjection(projection, props_.near_clip->getFloat(), props_.far_clip->getFloat());
  warnIf("Clipping", QString::fromStdString(clip));
  if (output_)
  {
    // The crosshairs are white on black, whatever the background colour.
    output_->setBackground(props_.testPattern() == TestPattern::Crosshairs ? Ogre::ColourValue::Black :
                                                                               props_.background->getOgreColor());
  }
  if (warp_)
  {
    warp_->setBackground(props_.background->getOgreColor());
  }
  context_->queueRender();
}

void ProjectorCameraDisplay::updateWarp()
{
  if (!warp_)
  {
    return;
  }
  const LensDistortion none;
  const LensDistortion& distortion = hasLens() ? pipeline_.lensSource().distortion() : none;
  const std::string error = hasLens() ? warp_->configure(lens(), distortion) : (warp_->clear(), std::string());
  const QString drawn = pipeline_.lensSource().distortionDrawn();
  if (!error.empty())
  {
    setStatus(rviz::StatusProperty::Warn, "Distortion",
              QString("%1: not applied, %2").arg(drawn, QString::fromStdString(error)));
  }
  else if (warp_->active())
  {
    showWarpStatus();
  }
}

void ProjectorCameraDisplay::showWarpStatus()
{
  warp_status_direct_ = warp_->readsDirectly();
  const QString cells = warp_->cells() != WarpCells::Occupied ?
                            QString() :
                            QString("; only its cells with something on them are drawn (read back %1)")
                                .arg(warp_status_direct_ ? "directly" : "whole");
  const std::string cells_note = warp_->cellsNote();
  const QString note = cells_note.empty() ? QString() : QString(" (%1)").arg(cells_note.c_str());
  setStatus(cells_note.empty() ? rviz::StatusProperty::Ok : rviz::StatusProperty::Warn, "Distortion",
            QString("%1: drawn through a %2x%3 warp (max %4 px from the lens model)%5%6")
                .arg(pipeline_.lensSource().distortionDrawn())
                .arg(warp_->grid().columns)
                .arg(warp_->grid().rows)
                .arg(warp_->gridError(), 0, 'f', 3)
                .arg(cells, note));
}

void ProjectorCameraDisplay::updateMaxLitHeight()
{
  markChanged();
  if (view_)
  {
    view_->setMaxLitHeight(props_.max_lit_height->getFloat());
    showCeiling();
  }
  context_->queueRender();
}

void ProjectorCameraDisplay::updateFrameRate()
{
  frame_clock_.setRate(props_.frame_rate->getInt(), output_ ? output_->refreshRate() : 0.0);
}

void ProjectorCameraDisplay::onFootprintPropertyChanged()
{
  markChanged();  // redraw the lines at the next frame
  updateFootprintVisible();
}

void ProjectorCameraDisplay::updateFootprintVisible()
{
  overlay_->setFootprintVisible(isEnabled() && props_.footprint->getBool() && hasLens() && pipeline_.poseOk());
}

void ProjectorCameraDisplay::updateTestPattern()
{
  markChanged();
  props_.showTestPatternOptions();
  if (!overlay_)
  {
    return;
  }
  overlay_->invalidate();  // the grid follows the fixed frame: compute it again
  if (props_.testPattern() != TestPattern::MetricGrid)
  {
    overlay_->clearGrid();
  }
  applyProjection();  // the background: black under the crosshairs
}

void ProjectorCameraDisplay::updateImageOutput()
{
  if (!image_publisher_)
  {
    return;
  }
  image_publisher_->stop();
  deleteStatus("Image output");
  if (props_.image_output->getBool())
  {
    const std::string error =
        image_publisher_->start(update_nh_, props_.image_topic->getStdString(), props_.image_rate->getFloat());
    if (!error.empty())
    {
      setStatus(rviz::StatusProperty::Error, "Image output", "Cannot advertise: " + QString::fromStdString(error));
    }
  }
}

void ProjectorCameraDisplay::fillScreenOptions()
{
  props_.fillScreenOptions();
}

void ProjectorCameraDisplay::updateOutput()
{
  if (!output_ || !isEnabled())
  {
    return;
  }
  rviz::WindowManagerInterface* rviz_window = context_->getWindowManager();  // null when embedded
  const OutputRequest request =
      props_.outputRequest(hasLens() ? lens().width() : 0, hasLens() ? lens().height() : 0,
                           ProjectorOutput::screenOf(rviz_window ? rviz_window->getParentWindow() : nullptr));
  output_->setTitle("Projector: " + getName());
  const OutputResult shown = output_->present(request);
  setStatus(statusLevel(shown.level), "Output", shown.text);
  updateFrameRate();
  gate_->invalidate();
}

ProjectorOutputWindow* ProjectorCameraDisplay::outputWindow() const
{
  return output_ ? output_->window() : nullptr;
}

void ProjectorCameraDisplay::setStatus(rviz::StatusProperty::Level level, const QString& name, const QString& text)
{
  if (statuses_.set(level, name, text))
  {
    Display::setStatus(level, name, text);
  }
}

void ProjectorCameraDisplay::deleteStatus(const QString& name)
{
  if (statuses_.remove(name))
  {
    Display::deleteStatus(name);
  }
}

void ProjectorCameraDisplay::clearStatuses()
{
  statuses_.clear();
  Display::clearStatuses();
}

void ProjectorCameraDisplay::warnIf(const QString& name, const QString& warning)
{
  warning.isEmpty() ? deleteStatus(name) : setStatus(rviz::StatusProperty::Warn, name, warning);
}
}  // namespace rviz_projector

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(rviz_projector::ProjectorCameraDisplay, rviz::Display)
