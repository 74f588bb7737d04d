#include "rviz_projector/displays/projector_camera_display.h"

#include <algorithm>
#include <cmath>

#include <OgreRenderWindow.h>
#include <OgreViewport.h>
#include <QGuiApplication>
#include <QScreen>
#include <QWidget>

#include <rviz/bit_allocator.h>
#include <rviz/config.h>
#include <rviz/display_context.h>
#include <rviz/display_group.h>
#include <rviz/load_resource.h>
#include <rviz/properties/display_group_visibility_property.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/string_property.h>
#include <rviz/properties/status_property.h>
#include <rviz/window_manager_interface.h>

#include "rviz_projector/displays/main_view_cost.h"
#include "rviz_projector/displays/projection_change_counter.h"
#include "rviz_projector/displays/projection_change_notifier.h"
#include "rviz_projector/displays/projection_gate.h"
#include "rviz_projector/displays/projector_crosshairs.h"
#include "rviz_projector/displays/projector_floor_overlay.h"
#include "rviz_projector/displays/projector_image_publisher.h"
#include "rviz_projector/displays/projector_lens_source.h"
#include "rviz_projector/displays/projector_output.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_projector/displays/projector_pose.h"
#include "rviz_projector/displays/projector_view.h"

namespace rviz_projector
{
namespace
{
/// The parts' Ok/Warn/Error levels are rviz's, value for value.
template <typename Level>
rviz::StatusProperty::Level levelOf(Level level)
{
  static_assert(int(Level::Ok) == rviz::StatusProperty::Ok && int(Level::Warn) == rviz::StatusProperty::Warn &&
                    int(Level::Error) == rviz::StatusProperty::Error,
                "status levels differ");
  return static_cast<rviz::StatusProperty::Level>(level);
}
}  // namespace

ProjectorCameraDisplay::ProjectorCameraDisplay() : props_(this)
{
}

ProjectorCameraDisplay::~ProjectorCameraDisplay()
{
  frame_timer_.stop();
  unsubscribe();
  image_publisher_.reset();
  output_.reset();  // listener, viewport, render window, widget
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

  // The gate first: it must hear a display's removal before the Visibility property forgets it.
  gate_ = std::make_unique<ProjectionGate>(context_->getRootDisplayGroup(), this);
  vis_bit_ = context_->visibilityBits()->allocBit();
  visibility_property_ = new rviz::DisplayGroupVisibilityProperty(
      vis_bit_, context_->getRootDisplayGroup(), this, "Visibility", true,
      "Displays shown in the projector view. New displays start hidden, except this package's path "
      "displays.");
  visibility_property_->setIcon(rviz::loadPixmap("package://rviz/icons/visibility.svg", true));
  addChild(visibility_property_, 0);
  // Defaults for the displays that exist now (a loaded config overrides them afterwards) and for
  // every display added later.
  gate_->attach(visibility_property_);

  output_ = std::make_unique<ProjectorOutput>("Projector: " + getName(), view_->camera(), this);
  connect(output_.get(), &ProjectorOutput::leaveFullScreenRequested, this,
          &ProjectorCameraDisplay::onLeaveFullScreenRequested);
  connect(output_.get(), &ProjectorOutput::closedByUser, this, &ProjectorCameraDisplay::onWindowClosed);
  image_publisher_ = std::make_unique<ProjectorImagePublisher>();
  overlay_ = std::make_unique<ProjectorFloorOverlay>(scene_manager_, scene_node_);
  crosshairs_ = std::make_unique<ProjectorCrosshairs>();

  connect(qApp, SIGNAL(screenAdded(QScreen*)), this, SLOT(onScreensChanged()));
  connect(qApp, SIGNAL(screenRemoved(QScreen*)), this, SLOT(onScreensChanged()));
  frame_timer_.setSingleShot(true);
  frame_timer_.setTimerType(Qt::PreciseTimer);
  connect(&frame_timer_, SIGNAL(timeout()), this, SLOT(onFrameTimer()));
  connect(&ProjectionChangeNotifier::instance(), &ProjectionChangeNotifier::changed, this,
          &ProjectorCameraDisplay::onSceneChanged, Qt::QueuedConnection);
  clock_.start();
  updateFrameRate();
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
  subscribe();
  updateOutput();
  frame_timer_.start(0);
}

void ProjectorCameraDisplay::onDisable()
{
  frame_timer_.stop();
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
  // Raise again, at once, every problem that still holds.
  transform_state_ = -1;
  overlay_->invalidate();
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
  // Labels of older configs become plain screen names.
  const std::string wanted = ProjectorOutput::screenName(props_.screen->getString());
  props_.screen->setString(QString::fromStdString(wanted));
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
  lens_source_.forget();
  onLensChanged();
  subscribe();
}

void ProjectorCameraDisplay::subscribe()
{
  if (!isEnabled() || props_.topic->getTopicStd().empty())
  {
    return;
  }
  const std::string error = lens_source_.subscribe(props_.topic->getTopicStd());
  if (error.empty())
  {
    setStatus(rviz::StatusProperty::Ok, "Topic", "OK");
  }
  else
  {
    setStatus(rviz::StatusProperty::Error, "Topic", "Error subscribing: " + QString::fromStdString(error));
  }
}

void ProjectorCameraDisplay::unsubscribe()
{
  lens_source_.unsubscribe();
}

void ProjectorCameraDisplay::showLensStatuses()
{
  const LensStatuses s = lens_source_.statuses(props_.topic->getTopic());
  setStatus(levelOf(s.camera_info_level), "CameraInfo", s.camera_info);
  for (const auto& warning : {std::make_pair(QString("Distortion"), s.distortion),
                              std::make_pair(QString("Field of view"), s.field_of_view)})
  {
    warnIf(warning.first, warning.second);
  }
}

void ProjectorCameraDisplay::onLensChanged()
{
  markChanged();
  showLensStatuses();
  const bool size_changed = hasLens() != (shown_size_.first > 0) ||
                            (hasLens() && (lens().width() != shown_size_.first || lens().height() != shown_size_.second));
  shown_size_ = hasLens() ? std::make_pair(lens().width(), lens().height()) : std::make_pair(0u, 0u);
  applyProjection();
  if (size_changed && isEnabled())
  {
    updateOutput();
  }
}

std::string ProjectorCameraDisplay::projectorFrame() const
{
  const std::string frame = props_.frame->getStdString();
  return frame.empty() ? lens_source_.frameId() : frame;
}

void ProjectorCameraDisplay::applyProjection()
{
  markChanged();
  if (!view_)
  {
    return;
  }
  const std::string clip = view_->setProjection(hasLens() ? &lens() : nullptr, props_.near_clip->getFloat(),
                                                props_.far_clip->getFloat());
  warnIf("Clipping", QString::fromStdString(clip));
  if (output_)
  {
    // The crosshairs are white on black, whatever the background colour.
    output_->setBackground(props_.testPattern() == TestPattern::Crosshairs ? Ogre::ColourValue::Black :
                                                                               props_.background->getOgreColor());
  }
  context_->queueRender();
}

void ProjectorCameraDisplay::updateFrameRate()
{
  const double refresh = output_ ? output_->refreshRate() : 0.0;
  pacer_.setPeriod(1.0 / FramePacer::rate(props_.frame_rate->getInt(), refresh));
}

void ProjectorCameraDisplay::onFootprintPropertyChanged()
{
  markChanged();  // redraw the lines at the next frame
  updateFootprintVisible();
}

void ProjectorCameraDisplay::updateFootprintVisible()
{
  overlay_->setFootprintVisible(isEnabled() && props_.footprint->getBool() && hasLens() && pose_ok_);
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

bool ProjectorCameraDisplay::updateCrosshairs()
{
  const bool wanted = props_.testPattern() == TestPattern::Crosshairs && hasLens();
  std::string problem;
  if (wanted && crosshairs_->update(lens().width(), lens().height(), props_.crosshair_rows->getInt(),
                                    props_.crosshair_cols->getInt(), problem))
  {
    markChanged();
  }
  warnIf("Test pattern", problem.empty() ? QString() : "No crosshairs: " + QString::fromStdString(problem));
  return wanted;
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
  props_.screen->clearOptions();
  props_.screen->addOption(kAutomaticScreen);
  for (QScreen* screen : QGuiApplication::screens())
  {
    props_.screen->addOption(screen->name());
  }
}

void ProjectorCameraDisplay::updateOutput()
{
  if (!output_ || !isEnabled())
  {
    return;
  }
  OutputRequest request;
  request.screen = ProjectorOutput::screenName(props_.screen->getString());
  request.full_screen = props_.full_screen->getBool();
  request.fsaa = props_.anti_aliasing->getBool() ? 4 : 0;
  request.image_width = hasLens() ? lens().width() : 0;
  request.image_height = hasLens() ? lens().height() : 0;
  // rviz's screen; the primary one while rviz's window has none yet (start-up) or when rviz is
  // embedded without a window manager.
  QScreen* rviz_screen =
      ProjectorOutput::screenOf(context_->getWindowManager() ? context_->getWindowManager()->getParentWindow() : nullptr);
  request.rviz_screen = rviz_screen ? rviz_screen : QGuiApplication::primaryScreen();
  output_->setTitle("Projector: " + getName());
  showOutputResult(output_->present(request));
  updateFrameRate();
  gate_->invalidate();
}

void ProjectorCameraDisplay::showOutputResult(const OutputResult& result)
{
  setStatus(levelOf(result.level), "Output", result.text);
}

void ProjectorCameraDisplay::onScreensChanged()
{
  if (isEnabled())
  {
    updateOutput();
  }
}

void ProjectorCameraDisplay::onLeaveFullScreenRequested()
{
  props_.full_screen->setBool(false);
}

void ProjectorCameraDisplay::onWindowClosed()
{
  setEnabled(false);
}

ProjectorOutputWindow* ProjectorCameraDisplay::outputWindow() const
{
  return output_ ? output_->window() : nullptr;
}

void ProjectorCameraDisplay::setTransformStatus(int state, const QString& text)
{
  transform_state_ = state;
  setStatus(state == ProjectorPose::Ok ? rviz::StatusProperty::Ok : rviz::StatusProperty::Error, "Transform", text);
}

bool ProjectorCameraDisplay::updateCameraPose()
{
  const std::string frame = projectorFrame();
  const double timeout = props_.tf_timeout->getFloat();
  const ProjectorPose pose = lookupProjectorPose(*context_->getTF2BufferPtr(), fixed_frame_.toStdString(), frame,
                                                 ros::Time::now().toSec(), timeout);
  tf_age_ = pose.state == ProjectorPose::Ok || pose.state == ProjectorPose::Stale ? pose.age : std::nan("");
  if (pose.state != ProjectorPose::Ok)
  {
    // A stale pose blanks the projector as a missing one does: no scene rather than an old picture.
    setTransformStatus(pose.state,
                       QString::fromStdString(describeProblem(pose, fixed_frame_.toStdString(), frame, timeout)));
    return false;
  }
  if (transform_state_ != ProjectorPose::Ok)
  {
    setTransformStatus(ProjectorPose::Ok, "OK");  // steady state: no status text built per frame
  }
  pose_ = pose.optical_to_fixed;
  view_->setPose(pose);
  return true;
}

void ProjectorCameraDisplay::updateFootprint()
{
  if (!hasLens() || !pose_ok_)
  {
    overlay_->setFootprintVisible(false);
    return;
  }
  const FloorOverlayResult lit = overlay_->update(lens(), pose_, own_changes_, props_.footprint->getBool(),
                                                  props_.testPattern() == TestPattern::MetricGrid);
  updateFootprintVisible();
  if (!lit.recomputed)
  {
    return;
  }
  if (lit.grid_changed)
  {
    markChanged();
  }
  if (lit.complete)
  {
    setStatus(rviz::StatusProperty::Ok, "Footprint",
              QString("Lit floor area %1 x %2 m, throw distance %3 m")
                  .arg(lit.width, 0, 'f', 2)
                  .arg(lit.depth, 0, 'f', 2)
                  .arg(lit.throw_distance, 0, 'f', 2));
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, "Footprint",
              "Part of the image does not reach the floor (projector aims at or above the horizon, or "
              "the floor is farther than 10 m)");
  }
}

bool ProjectorCameraDisplay::prepareFrame()
{
  if (!output_ || !output_->viewport())
  {
    return false;
  }
  pose_ok_ = hasLens() && updateCameraPose();
  if (!hasLens() && transform_state_ != -1)
  {
    deleteStatus("Transform");
    transform_state_ = -1;
  }
  updateFootprint();
  crosshairs_shown_ = updateCrosshairs();
  if (output_->fitViewport(hasLens() ? lens().width() : 0, hasLens() ? lens().height() : 0))
  {
    warnIf("Scaling", hasLens() ? output_->scalingNote(lens().width(), lens().height()) : QString());
  }
  return true;
}

void ProjectorCameraDisplay::preRenderTargetUpdate(const Ogre::RenderTargetEvent& /*event*/)
{
  // rviz's camera display does the same: other camera-like displays change the displays' bits.
  if (visibility_property_)
  {
    visibility_property_->update();
  }
  // The frustum never shows in the projector's own view.
  overlay_->setFootprintVisibilityFlags(~vis_bit_);
  // The crosshairs' camera sees only them (nothing else is in its scene), with or without a pose.
  Ogre::Camera* camera = crosshairs_shown_ ? crosshairs_->camera() : view_->camera();
  if (Ogre::Viewport* viewport = output_->viewport(); viewport && viewport->getCamera() != camera)
  {
    viewport->setCamera(camera);
  }
  output_->setVisibilityMask(crosshairs_shown_ ? ~0u : hasLens() && pose_ok_ ? vis_bit_ : 0u);
}

void ProjectorCameraDisplay::onFrameTimer()
{
  if (!isEnabled())
  {
    return;
  }
  // Only this display's own CameraInfo subscription: never rviz's global queue.
  if (lens_source_.poll())
  {
    onLensChanged();
  }
  renderNow();
  rate_meter_.sample(static_cast<double>(clock_.nsecsElapsed()) * 1e-9, frames_rendered_);
  if (isEnabled())
  {
    const double delay = pacer_.tick(static_cast<double>(clock_.nsecsElapsed()) * 1e-9);
    frame_timer_.start(static_cast<int>(std::ceil(delay * 1000.0)));
  }
}

void ProjectorCameraDisplay::onSceneChanged()
{
  // A frame now rather than at the next deadline, unless one went out less than a period ago (the
  // Frame rate limit holds: early frames only replace deadlines that rendered nothing).
  const double now = static_cast<double>(clock_.nsecsElapsed()) * 1e-9;
  if (isEnabled() && frame_timer_.isActive() && rate_meter_.sinceLastFrame(now) >= pacer_.period())
  {
    frame_timer_.start(0);
  }
}

void ProjectorCameraDisplay::renderNow()
{
  if (!isEnabled() || !output_ || !output_->isShown() || !prepareFrame())
  {
    return;
  }
  const bool publish = image_publisher_->due() && hasLens();
  FrameState state;
  state.pose = view_->poseKey();
  state.changes = ProjectionChangeCounter::value() + own_changes_;
  state.visibility = gate_->visibilitySignature();
  state.image = output_->imageRect();
  state.drawable = hasLens() && (pose_ok_ || crosshairs_shown_);
  if (output_->takeRepaintRequest())
  {
    gate_->invalidate();  // exposed again: the window's content must be drawn anew
  }
  if (!gate_->needsFrame(state) && !publish)
  {
    ++frames_skipped_;  // the projector already shows exactly this
    return;
  }
  output_->render(!publish);
  ++frames_rendered_;
  if (publish)
  {
    image_publisher_->publish(output_->renderWindow(), output_->imageRect(), lens(), projectorFrame());
    output_->swap();
  }
}

void ProjectorCameraDisplay::setStatus(rviz::StatusProperty::Level level, const QString& name, const QString& text)
{
  auto it = status_cache_.find(name);
  if (it != status_cache_.end() && it->second.first == level && it->second.second == text)
  {
    return;
  }
  status_cache_[name] = {level, text};
  Display::setStatus(level, name, text);
}

void ProjectorCameraDisplay::warnIf(const QString& name, const QString& warning)
{
  if (warning.isEmpty())
  {
    deleteStatus(name);
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, name, warning);
  }
}

void ProjectorCameraDisplay::deleteStatus(const QString& name)
{
  if (status_cache_.erase(name) > 0)
  {
    Display::deleteStatus(name);
  }
}

void ProjectorCameraDisplay::clearStatuses()
{
  status_cache_.clear();
  Display::clearStatuses();
}
}  // namespace rviz_projector

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(rviz_projector::ProjectorCameraDisplay, rviz::Display)
