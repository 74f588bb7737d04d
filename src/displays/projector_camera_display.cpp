#include "rviz_projector/displays/projector_camera_display.h"

#include <algorithm>
#include <cmath>

#include <OgreCamera.h>
#include <OgreMatrix4.h>
#include <OgreRenderSystem.h>
#include <OgreRenderSystemCapabilities.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneNode.h>
#include <OgreViewport.h>
#include <QCoreApplication>
#include <QGuiApplication>
#include <QScreen>
#include <QWidget>
#include <QWindow>

#include <rviz/bit_allocator.h>
#include <rviz/config.h>
#include <rviz/display_context.h>
#include <rviz/display_group.h>
#include <rviz/frame_manager.h>
#include <rviz/load_resource.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/display_group_visibility_property.h>
#include <rviz/properties/enum_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/ros_topic_property.h>
#include <rviz/properties/status_property.h>
#include <rviz/properties/string_property.h>
#include <rviz/render_panel.h>
#include <rviz/view_manager.h>
#include <rviz/window_manager_interface.h>
#include <sensor_msgs/Image.h>
#include <tf2_ros/buffer.h>

#include "rviz_projector/core/floor_footprint.h"
#include "rviz_projector/core/floor_grid.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/displays/config_check.h"
#include "rviz_projector/displays/floor_mesh.h"
#include "rviz_projector/displays/main_view_cost.h"
#include "rviz_projector/displays/ogre_name.h"
#include "rviz_projector/displays/projection_change_counter.h"
#include "rviz_projector/displays/projector_footprint_visual.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_projector/displays/render_target_readback.h"
#include "rviz_projector/ros/ros_conversions.h"

namespace rviz_projector
{
namespace
{
/// Rays that miss the floor are drawn to this distance in the main view, metres.
constexpr double kFrustumLength = 10.0;
/// Test-pattern extent around the lit area, metres, and its bound.
constexpr double kGridMargin = 0.5;
constexpr double kGridMaxHalfExtent = 25.0;

QString screenLabel(const QScreen* screen)
{
  const QRect g = screen->geometry();
  return QString("%1 (%2x%3 at %4,%5)").arg(screen->name()).arg(g.width()).arg(g.height()).arg(g.x()).arg(g.y());
}

QString screenNameOf(const QString& label)
{
  const int cut = label.indexOf(" (");
  return cut < 0 ? label.trimmed() : label.left(cut).trimmed();
}

QScreen* screenOfRviz(rviz::DisplayContext* context)
{
  // The window manager is null when rviz is embedded (librviz, tests): fall back to the primary.
  rviz::WindowManagerInterface* wm = context->getWindowManager();
  QWidget* main_window = wm ? wm->getParentWindow() : nullptr;
  if (main_window && main_window->window()->windowHandle())
  {
    return main_window->window()->windowHandle()->screen();
  }
  return QGuiApplication::primaryScreen();
}

bool projectorDisplayShownByDefault(const rviz::Display* display)
{
  const QString id = display->getClassId();
  return id.startsWith("rviz_projector/") && id != "rviz_projector/ProjectorCamera";
}
}  // namespace

ProjectorCameraDisplay::ProjectorCameraDisplay()
{
  topic_property_ = new rviz::RosTopicProperty(
      "Topic", kDefaultTopic, QString::fromStdString(ros::message_traits::datatype<sensor_msgs::CameraInfo>()),
      "sensor_msgs/CameraInfo of the projector: resolution and lens (P, or K when P is all zero).", this,
      SLOT(updateTopic()), this);
  frame_property_ = new rviz::StringProperty(
      "Frame", "",
      "tf frame of the projector's optical frame (z forward, x right, y down). Empty: the CameraInfo "
      "header's frame_id.",
      this, SLOT(updateCameraSettings()), this);
  screen_property_ = new rviz::EnumProperty(
      "Output screen", kAutomaticScreen,
      "Screen the projector is plugged into. Automatic: a screen other than rviz's, if there is one.", this,
      SLOT(updateOutput()), this);
  connect(screen_property_, SIGNAL(requestOptions(EnumProperty*)), this, SLOT(fillScreenOptions()));
  full_screen_property_ = new rviz::BoolProperty(
      "Full screen", true,
      "Full screen on the output screen (Esc leaves it). Off: a normal window, e.g. for setting up on a "
      "laptop. With a single screen the window always opens windowed, never covering rviz.",
      this, SLOT(updateOutput()), this);
  background_property_ = new rviz::ColorProperty("Background color", QColor(0, 0, 0),
                                                 "Colour where nothing is drawn. Black projects no light.", this,
                                                 SLOT(updateCameraSettings()), this);
  near_clip_property_ = new rviz::FloatProperty("Near clip", 0.05f, "Nearest distance drawn, metres.", this,
                                                SLOT(updateCameraSettings()), this);
  near_clip_property_->setMin(0.001f);
  near_clip_property_->setMax(100.0f);
  far_clip_property_ = new rviz::FloatProperty("Far clip", 50.0f, "Farthest distance drawn, metres.", this,
                                               SLOT(updateCameraSettings()), this);
  far_clip_property_->setMin(0.01f);
  far_clip_property_->setMax(10000.0f);
  frame_rate_property_ = new rviz::IntProperty(
      "Frame rate limit", 60, "Most frames per second rendered into the output window (the projector's refresh).",
      this, SLOT(updateFrameRate()), this);
  frame_rate_property_->setMin(1);
  frame_rate_property_->setMax(240);
  anti_aliasing_property_ = new rviz::BoolProperty(
      "Anti-aliasing", false,
      "Smooth edges with 4x multisampling. Off by default: projected arrows are solid shapes, and on "
      "software or integrated graphics multisampling costs most of the frame time.",
      this, SLOT(updateOutput()), this);
  footprint_property_ = new rviz::BoolProperty(
      "Footprint in main view", true,
      "Draw the projector's frustum and the area it lights on the floor (z = 0) in rviz's main view.", this,
      SLOT(onFootprintPropertyChanged()), this);
  test_pattern_property_ = new rviz::BoolProperty(
      "Test pattern", false,
      "Project a metric grid on the floor: 10 cm cells, bold lines every metre, a cross at the fixed "
      "frame's origin. Check the calibration with a tape measure.",
      this, SLOT(updateTestPattern()), this);
  image_output_property_ = new rviz::BoolProperty(
      "Image output", false,
      "Also publish the rendered view as sensor_msgs/Image (+ CameraInfo) for remote monitoring or recording.",
      this, SLOT(updateImageOutput()), this);
  image_topic_property_ = new rviz::StringProperty("Image topic", "/projector/rendered/image",
                                                   "Topic of the published image; CameraInfo goes to the "
                                                   "sibling topic camera_info.",
                                                   image_output_property_, SLOT(updateImageOutput()), this);
  image_rate_property_ = new rviz::FloatProperty("Image rate", 10.0f, "Images published per second.",
                                                 image_output_property_, SLOT(updateImageOutput()), this);
  image_rate_property_->setMin(0.1f);
  image_rate_property_->setMax(120.0f);
}

ProjectorCameraDisplay::~ProjectorCameraDisplay()
{
  render_timer_.stop();
  unsubscribe();
  destroyWindow();
  footprint_visual_.reset();
  grid_mesh_.reset();
  if (camera_node_)
  {
    camera_node_->detachAllObjects();
    scene_manager_->destroySceneNode(camera_node_);
  }
  if (camera_)
  {
    scene_manager_->destroyCamera(camera_);
  }
  if (vis_bit_ != 0)
  {
    context_->visibilityBits()->freeBits(vis_bit_);
  }
}

void ProjectorCameraDisplay::onInitialize()
{
  camera_ = scene_manager_->createCamera(uniqueOgreName("rviz_projector_camera_"));
  camera_node_ = scene_manager_->getRootSceneNode()->createChildSceneNode();
  camera_node_->attachObject(camera_);
  updateCameraSettings();

  vis_bit_ = context_->visibilityBits()->allocBit();
  if (vis_bit_ == 0)
  {
    setStatus(rviz::StatusProperty::Error, "Visibility",
              "All 32 visibility bits are in use (too many camera displays): the projector view stays empty");
  }
  visibility_property_ = new rviz::DisplayGroupVisibilityProperty(
      vis_bit_, context_->getRootDisplayGroup(), this, "Visibility", true,
      "Displays shown in the projector view. New displays start hidden, except this package's path "
      "displays.");
  visibility_property_->setIcon(rviz::loadPixmap("package://rviz/icons/visibility.svg", true));
  addChild(visibility_property_, 0);
  // Defaults for the displays that exist now (a loaded config overrides them afterwards) and for
  // every display added later.
  rviz::DisplayGroup* group = context_->getRootDisplayGroup();
  for (int i = 0; i < group->numDisplays(); ++i)
  {
    onDisplayAdded(group->getDisplayAt(i));
  }
  connect(group, SIGNAL(displayAdded(rviz::Display*)), this, SLOT(onDisplayAdded(rviz::Display*)));

  footprint_visual_ = std::make_unique<ProjectorFootprintVisual>(scene_manager_, scene_node_);
  footprint_visual_->setVisible(false);
  grid_mesh_ = std::make_unique<FloorMesh>(scene_manager_, scene_node_);

  connect(qApp, SIGNAL(screenAdded(QScreen*)), this, SLOT(onScreensChanged()));
  connect(qApp, SIGNAL(screenRemoved(QScreen*)), this, SLOT(onScreensChanged()));
  connect(&render_timer_, SIGNAL(timeout()), this, SLOT(renderNow()));
  updateFrameRate();
  setStatus(rviz::StatusProperty::Warn, "CameraInfo",
            QString("No CameraInfo received on %1").arg(topic_property_->getTopic()));
}

void ProjectorCameraDisplay::onDisplayAdded(rviz::Display* display)
{
  if (!visibility_property_ || display == this || qobject_cast<rviz::DisplayGroup*>(display))
  {
    return;
  }
  // The visibility property lists one child per display of the group, in the group's order,
  // leaving out this display.
  rviz::DisplayGroup* group = context_->getRootDisplayGroup();
  int index = 0;
  for (int i = 0; i < group->numDisplays(); ++i)
  {
    rviz::Display* d = group->getDisplayAt(i);
    if (d == display)
    {
      if (index < visibility_property_->numChildren())
      {
        setDefaultVisibility(visibility_property_->childAt(index), display);
      }
      return;
    }
    if (d != this)
    {
      ++index;
    }
  }
}

void ProjectorCameraDisplay::setDefaultVisibility(rviz::Property* child, rviz::Display* display)
{
  child->setValue(projectorDisplayShownByDefault(display));
}

void ProjectorCameraDisplay::onEnable()
{
  checkMainViewCost();
  subscribe();
  if (!window_)
  {
    createWindow();
  }
  updateOutput();
  render_timer_.start();
}

void ProjectorCameraDisplay::checkMainViewCost()
{
  // The main view's render window and the renderer are fixed for the life of rviz.
  rviz::ViewManager* views = context_->getViewManager();
  rviz::RenderPanel* panel = views != nullptr ? views->getRenderPanel() : nullptr;
  Ogre::RenderWindow* main_window = panel != nullptr ? panel->getRenderWindow() : nullptr;
  Ogre::RenderSystem* render_system = Ogre::Root::getSingleton().getRenderSystem();
  const Ogre::RenderSystemCapabilities* capabilities =
      render_system != nullptr ? render_system->getCapabilities() : nullptr;
  const std::string warning = main_window != nullptr && capabilities != nullptr ?
                                  mainViewCostWarning(main_window->getFSAA(), capabilities->getDeviceName()) :
                                  std::string();
  if (warning.empty())
  {
    deleteStatus("Main view");
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, "Main view", QString::fromStdString(warning));
  }
}

void ProjectorCameraDisplay::onDisable()
{
  render_timer_.stop();
  unsubscribe();
  if (window_)
  {
    window_->hide();
  }
  footprint_visual_->setVisible(false);
}

void ProjectorCameraDisplay::reset()
{
  Display::reset();
  checkMainViewCost();
  last_info_.reset();
  has_lens_ = false;
  markChanged();
  setStatus(rviz::StatusProperty::Warn, "CameraInfo",
            QString("No CameraInfo received on %1").arg(topic_property_->getTopic()));
  // A projector's CameraInfo is usually published once, latched: subscribe again to get it back.
  if (isEnabled() && info_sub_)
  {
    unsubscribe();
    subscribe();
  }
}

void ProjectorCameraDisplay::load(const rviz::Config& config)
{
  Display::load(config);
  ConfigCheck check;
  for (rviz::Property* p : {static_cast<rviz::Property*>(near_clip_property_), static_cast<rviz::Property*>(far_clip_property_),
                            static_cast<rviz::Property*>(frame_rate_property_)})
  {
    check.number(config.mapGetChild(p->getName()), p);
  }
  check.number(config.mapGetChild(image_output_property_->getName()).mapGetChild(image_rate_property_->getName()),
               image_rate_property_);
  // An output screen that is not connected is said at once, even while the display is disabled
  // (placing the window, when enabled, keeps the status up to date).
  QString why;
  chooseScreen(why);
  if (!why.isEmpty() && !isEnabled())
  {
    setStatus(rviz::StatusProperty::Warn, "Output", why);
  }
  if (check.report().isEmpty())
  {
    deleteStatus("Config");
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, "Config", "Unusable values in the config replaced: " + check.report());
  }
}

void ProjectorCameraDisplay::fixedFrameChanged()
{
  updateTestPattern();
}

void ProjectorCameraDisplay::setTopic(const QString& topic, const QString& /*datatype*/)
{
  topic_property_->setString(topic);
}

void ProjectorCameraDisplay::updateTopic()
{
  unsubscribe();
  reset();
  subscribe();
}

void ProjectorCameraDisplay::subscribe()
{
  if (!isEnabled() || topic_property_->getTopicStd().empty())
  {
    return;
  }
  try
  {
    info_sub_ = update_nh_.subscribe(topic_property_->getTopicStd(), 1, &ProjectorCameraDisplay::cameraInfoCallback,
                                     this);
    setStatus(rviz::StatusProperty::Ok, "Topic", "OK");
  }
  catch (const ros::Exception& e)
  {
    setStatus(rviz::StatusProperty::Error, "Topic", QString("Error subscribing: ") + e.what());
  }
}

void ProjectorCameraDisplay::unsubscribe()
{
  info_sub_.shutdown();
}

void ProjectorCameraDisplay::cameraInfoCallback(const sensor_msgs::CameraInfo::ConstPtr& msg)
{
  last_info_ = msg;
  applyCameraInfo();
}

void ProjectorCameraDisplay::applyCameraInfo()
{
  if (!last_info_)
  {
    return;
  }
  info_frame_ = last_info_->header.frame_id;
  PinholeModel lens;
  const LensCheck check = PinholeModel::fromCalibration(toLensCalibration(*last_info_), lens);
  if (!check.ok())
  {
    has_lens_ = false;
    markChanged();
    setStatus(rviz::StatusProperty::Error, "CameraInfo",
              QString("Unusable CameraInfo: %1; the projector shows background only")
                  .arg(QString::fromStdString(check.error)));
    deleteStatus("Distortion");
    return;
  }
  markChanged();
  const bool size_changed = !has_lens_ || lens.width() != lens_.width() || lens.height() != lens_.height();
  lens_ = lens;
  has_lens_ = true;
  setStatus(rviz::StatusProperty::Ok, "CameraInfo",
            QString("%1x%2, fx %3, fy %4, cx %5, cy %6")
                .arg(lens_.width())
                .arg(lens_.height())
                .arg(lens_.fx())
                .arg(lens_.fy())
                .arg(lens_.cx())
                .arg(lens_.cy()));
  if (check.warning.empty())
  {
    deleteStatus("Distortion");
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, "Distortion", QString::fromStdString(check.warning));
  }
  updateCameraSettings();
  if (size_changed && isEnabled())
  {
    updateOutput();
  }
}

std::string ProjectorCameraDisplay::projectorFrame() const
{
  const std::string frame = frame_property_->getStdString();
  return frame.empty() ? info_frame_ : frame;
}

void ProjectorCameraDisplay::updateCameraSettings()
{
  markChanged();
  if (!camera_)
  {
    return;
  }
  double near_clip = near_clip_property_->getFloat();
  double far_clip = far_clip_property_->getFloat();
  if (far_clip <= near_clip)
  {
    far_clip = near_clip * 1000.0;
    setStatus(rviz::StatusProperty::Warn, "Clipping",
              QString("Far clip must be beyond near clip: using %1 m").arg(far_clip));
  }
  else
  {
    deleteStatus("Clipping");
  }
  camera_->setNearClipDistance(static_cast<Ogre::Real>(near_clip));
  camera_->setFarClipDistance(static_cast<Ogre::Real>(far_clip));
  if (has_lens_)
  {
    const auto m = lens_.glProjectionMatrix(near_clip, far_clip);
    Ogre::Matrix4 projection;
    for (int r = 0; r < 4; ++r)
    {
      for (int c = 0; c < 4; ++c)
      {
        projection[r][c] = static_cast<Ogre::Real>(m[4 * r + c]);
      }
    }
    camera_->setCustomProjectionMatrix(true, projection);
  }
  if (viewport_)
  {
    viewport_->setBackgroundColour(background_property_->getOgreColor());
  }
  context_->queueRender();
}

void ProjectorCameraDisplay::updateFrameRate()
{
  render_timer_.setInterval(std::max(1, 1000 / std::max(1, frame_rate_property_->getInt())));
}

void ProjectorCameraDisplay::onFootprintPropertyChanged()
{
  markChanged();  // redraw the lines at the next frame
  updateFootprintVisible();
}

void ProjectorCameraDisplay::updateFootprintVisible()
{
  footprint_visual_->setVisible(isEnabled() && footprint_property_->getBool() && has_lens_ && pose_ok_);
}

void ProjectorCameraDisplay::updateTestPattern()
{
  markChanged();
  if (!grid_mesh_)
  {
    return;
  }
  if (!test_pattern_property_->getBool())
  {
    grid_mesh_->clear();
    grid_triangles_.clear();
  }
  context_->queueRender();
}

void ProjectorCameraDisplay::updateImageOutput()
{
  image_pub_.shutdown();
  image_info_pub_.shutdown();
  if (image_output_property_->getBool())
  {
    const std::string topic = image_topic_property_->getStdString();
    try
    {
      image_pub_ = update_nh_.advertise<sensor_msgs::Image>(topic, 1);
      const std::string::size_type slash = topic.rfind('/');
      const std::string info_topic = (slash == std::string::npos ? std::string() : topic.substr(0, slash + 1)) +
                                     "camera_info";
      image_info_pub_ = update_nh_.advertise<sensor_msgs::CameraInfo>(info_topic, 1);
      deleteStatus("Image output");
    }
    catch (const ros::Exception& e)
    {
      setStatus(rviz::StatusProperty::Error, "Image output", QString("Cannot advertise: ") + e.what());
    }
  }
  else
  {
    deleteStatus("Image output");
  }
}

void ProjectorCameraDisplay::fillScreenOptions()
{
  screen_property_->clearOptions();
  screen_property_->addOption(kAutomaticScreen);
  for (QScreen* screen : QGuiApplication::screens())
  {
    screen_property_->addOption(screenLabel(screen));
  }
}

QScreen* ProjectorCameraDisplay::chooseScreen(QString& why) const
{
  const QList<QScreen*> screens = QGuiApplication::screens();
  if (screens.isEmpty())
  {
    why = "No screen is connected";
    return nullptr;
  }
  const QString wanted = screenNameOf(screen_property_->getString());
  if (wanted != kAutomaticScreen)
  {
    for (QScreen* screen : screens)
    {
      if (screen->name() == wanted)
      {
        return screen;
      }
    }
    why = QString("Screen '%1' is not connected").arg(wanted);
  }
  QScreen* rviz_screen = screenOfRviz(context_);
  for (QScreen* screen : screens)
  {
    if (screen != rviz_screen)
    {
      return screen;
    }
  }
  return rviz_screen ? rviz_screen : screens.front();
}

bool ProjectorCameraDisplay::wantsFullScreen() const
{
  return full_screen_property_->getBool() && QGuiApplication::screens().size() >= 2;
}

int ProjectorCameraDisplay::wantedFsaa() const
{
  return anti_aliasing_property_->getBool() ? 4 : 0;
}

void ProjectorCameraDisplay::createWindow()
{
  window_ = std::make_unique<ProjectorOutputWindow>("Projector: " + getName(), wantsFullScreen(), wantedFsaa());
  Ogre::RenderWindow* render_window = window_->renderWindow();
  render_window->addListener(this);
  viewport_ = render_window->addViewport(camera_);
  viewport_->setOverlaysEnabled(false);
  viewport_->setShadowsEnabled(false);
  viewport_->setSkiesEnabled(false);
  viewport_->setClearEveryFrame(true);
  viewport_->setBackgroundColour(background_property_->getOgreColor());
  viewport_->setVisibilityMask(vis_bit_);
  have_last_frame_ = false;  // a new window has nothing in it yet
  connect(window_.get(), SIGNAL(leaveFullScreenRequested()), this, SLOT(onLeaveFullScreenRequested()));
  connect(window_.get(), SIGNAL(closedByUser()), this, SLOT(onWindowClosed()));
}

void ProjectorCameraDisplay::destroyWindow()
{
  if (!window_)
  {
    return;
  }
  // Order matters: listener, viewport, render window (in the widget's destructor), widget.
  Ogre::RenderWindow* render_window = window_->renderWindow();
  render_window->removeListener(this);
  render_window->removeAllViewports();
  viewport_ = nullptr;
  window_->disconnect(this);
  window_.reset();
}

void ProjectorCameraDisplay::updateOutput()
{
  if (!window_ || !isEnabled())
  {
    return;
  }
  QString why;
  QScreen* screen = chooseScreen(why);
  const bool single_screen = QGuiApplication::screens().size() < 2;
  if (wantsFullScreen() != window_->isFullScreenOn() || window_->fsaa() != wantedFsaa())
  {
    // Frameless or framed, and the multisampling, are fixed per native window: a new one.
    destroyWindow();
    createWindow();
  }
  const QSize image_size = has_lens_ ? QSize(static_cast<int>(lens_.width()), static_cast<int>(lens_.height()))
                                     : QSize(1280, 800);
  if (!screen)
  {
    window_->hide();
    setStatus(rviz::StatusProperty::Warn, "Output", why + ": output window hidden until a screen appears");
    return;
  }
  window_->present(screen, image_size, single_screen);
  const QString text =
      QString("%1 on %2").arg(window_->isFullScreenOn() ? "Full screen" : "Window").arg(screenLabel(screen));
  if (single_screen)
  {
    // Also what a user sees right after unplugging the projector.
    setStatus(rviz::StatusProperty::Warn, "Output",
              (why.isEmpty() ? QString() : why + "; ") + "only one screen is connected: " + text +
                  ", in a corner so as not to cover rviz (connect the projector as an extended desktop)");
  }
  else
  {
    setStatus(why.isEmpty() ? rviz::StatusProperty::Ok : rviz::StatusProperty::Warn, "Output",
              why.isEmpty() ? text : why + "; using " + text);
  }
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
  full_screen_property_->setBool(false);
}

void ProjectorCameraDisplay::onWindowClosed()
{
  setEnabled(false);
}

bool ProjectorCameraDisplay::updateCameraPose()
{
  const std::string frame = projectorFrame();
  if (frame.empty())
  {
    setStatus(rviz::StatusProperty::Error, "Transform",
              "No projector frame: the CameraInfo header has no frame_id and the Frame property is empty");
    return false;
  }
  geometry_msgs::TransformStamped t;
  try
  {
    // Latest available transform: a latched CameraInfo carries an old stamp, and tf extrapolation
    // errors must not blank the projection.
    t = context_->getTF2BufferPtr()->lookupTransform(fixed_frame_.toStdString(), frame, ros::Time(0));
  }
  catch (const tf2::TransformException& e)
  {
    setStatus(rviz::StatusProperty::Error, "Transform",
              QString("No transform from projector frame [%1] to fixed frame [%2]: %3")
                  .arg(QString::fromStdString(frame), fixed_frame_, e.what()));
    return false;
  }
  const auto& q = t.transform.rotation;
  const auto& p = t.transform.translation;
  if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z) || !std::isfinite(q.w) ||
      !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
  {
    setStatus(rviz::StatusProperty::Error, "Transform",
              QString("Transform of [%1] contains NaN/Inf").arg(QString::fromStdString(frame)));
    return false;
  }
  setStatus(rviz::StatusProperty::Ok, "Transform", "OK");
  // Optical frame (z forward, y down) -> OGRE camera (looks down -z, y up): half turn about x.
  const Ogre::Quaternion optical(static_cast<Ogre::Real>(q.w), static_cast<Ogre::Real>(q.x),
                                 static_cast<Ogre::Real>(q.y), static_cast<Ogre::Real>(q.z));
  camera_node_->setPosition(static_cast<Ogre::Real>(p.x), static_cast<Ogre::Real>(p.y), static_cast<Ogre::Real>(p.z));
  camera_node_->setOrientation(optical * Ogre::Quaternion(Ogre::Degree(180), Ogre::Vector3::UNIT_X));
  return true;
}

void ProjectorCameraDisplay::updateFootprint()
{
  if (!has_lens_ || !pose_ok_)
  {
    footprint_visual_->setVisible(false);
    return;
  }
  const Ogre::Vector3 position = camera_node_->getPosition();
  const Ogre::Quaternion& orientation = camera_node_->getOrientation();
  // Unchanged pose, lens and settings: the footprint and its statuses are as they were.
  const std::array<float, 7> key{position.x, position.y, position.z, orientation.w, orientation.x, orientation.y,
                                 orientation.z};
  if (key == footprint_key_ && own_changes_ == footprint_changes_)
  {
    updateFootprintVisible();
    return;
  }
  footprint_key_ = key;
  footprint_changes_ = own_changes_;
  const Ogre::Quaternion optical = orientation * Ogre::Quaternion(Ogre::Degree(180), Ogre::Vector3::UNIT_X);
  const RigidTransform pose =
      RigidTransform::fromQuaternion(optical.x, optical.y, optical.z, optical.w, Vec3{position.x, position.y, position.z});
  const FloorFootprint footprint(lens_, pose, kFrustumLength);
  if (footprint_property_->getBool())
  {
    footprint_visual_->update(footprint);
  }
  updateFootprintVisible();
  if (footprint.complete())
  {
    setStatus(rviz::StatusProperty::Ok, "Footprint",
              QString("Lit floor area %1 x %2 m, throw distance %3 m")
                  .arg(footprint.width(), 0, 'f', 2)
                  .arg(footprint.depth(), 0, 'f', 2)
                  .arg(footprint.throwDistance(), 0, 'f', 2));
  }
  else
  {
    setStatus(rviz::StatusProperty::Warn, "Footprint",
              "Part of the image does not reach the floor (projector aims at or above the horizon, or "
              "the floor is farther than 10 m)");
  }
  if (test_pattern_property_->getBool())
  {
    Vec2 lo{position.x - kGridMargin, position.y - kGridMargin};
    Vec2 hi{position.x + kGridMargin, position.y + kGridMargin};
    for (const Vec3& c : footprint.corners())
    {
      lo = Vec2{std::min(lo.x, c.x - kGridMargin), std::min(lo.y, c.y - kGridMargin)};
      hi = Vec2{std::max(hi.x, c.x + kGridMargin), std::max(hi.y, c.y + kGridMargin)};
    }
    // Whole metres, bounded, so the mesh is rebuilt only when the lit area moves a lot.
    lo = Vec2{std::max(std::floor(lo.x), position.x - kGridMaxHalfExtent),
              std::max(std::floor(lo.y), position.y - kGridMaxHalfExtent)};
    hi = Vec2{std::min(std::ceil(hi.x), position.x + kGridMaxHalfExtent),
              std::min(std::ceil(hi.y), position.y + kGridMaxHalfExtent)};
    std::vector<Vec2> triangles;
    FloorGrid(Vec2{std::floor(lo.x), std::floor(lo.y)}, Vec2{std::ceil(hi.x), std::ceil(hi.y)}).appendTriangles(triangles);
    if (triangles.size() != grid_triangles_.size() ||
        (!triangles.empty() && (triangles.front().x != grid_triangles_.front().x ||
                                triangles.front().y != grid_triangles_.front().y)))
    {
      grid_triangles_.swap(triangles);
      grid_mesh_->setFlatTriangles(grid_triangles_, 0.0, Ogre::ColourValue::White);
      markChanged();
    }
  }
}

void ProjectorCameraDisplay::updateViewport()
{
  if (!viewport_)
  {
    return;
  }
  int left, top, width, height;
  viewportPixels(left, top, width, height);
  Ogre::RenderWindow* rw = window_->renderWindow();
  const double ww = rw->getWidth();
  const double wh = rw->getHeight();
  if (ww <= 0 || wh <= 0)
  {
    return;
  }
  viewport_->setDimensions(static_cast<Ogre::Real>(left / ww), static_cast<Ogre::Real>(top / wh),
                           static_cast<Ogre::Real>(width / ww), static_cast<Ogre::Real>(height / wh));
  if (has_lens_ && (width != static_cast<int>(lens_.width()) || height != static_cast<int>(lens_.height())))
  {
    setStatus(rviz::StatusProperty::Warn, "Scaling",
              QString("Window %1x%2 differs from the %3x%4 image: scaled to %5x%6, letterboxed (not 1:1)")
                  .arg(rw->getWidth())
                  .arg(rw->getHeight())
                  .arg(lens_.width())
                  .arg(lens_.height())
                  .arg(width)
                  .arg(height));
  }
  else
  {
    deleteStatus("Scaling");
  }
}

void ProjectorCameraDisplay::viewportPixels(int& left, int& top, int& width, int& height) const
{
  left = top = width = height = 0;
  if (!window_)
  {
    return;
  }
  Ogre::RenderWindow* rw = window_->renderWindow();
  const int ww = static_cast<int>(rw->getWidth());
  const int wh = static_cast<int>(rw->getHeight());
  if (!has_lens_)
  {
    width = ww;
    height = wh;
    return;
  }
  const double iw = lens_.width();
  const double ih = lens_.height();
  if (static_cast<int>(iw) <= ww && static_cast<int>(ih) <= wh && (static_cast<int>(iw) == ww || static_cast<int>(ih) == wh))
  {
    // Exact fit along one axis: no scaling at all (1:1 pixels), letterbox the other axis.
    width = static_cast<int>(iw);
    height = static_cast<int>(ih);
  }
  else
  {
    const double scale = std::min(ww / iw, wh / ih);
    width = std::max(1, static_cast<int>(std::lround(iw * scale)));
    height = std::max(1, static_cast<int>(std::lround(ih * scale)));
  }
  left = (ww - width) / 2;
  top = (wh - height) / 2;
}

void ProjectorCameraDisplay::preRenderTargetUpdate(const Ogre::RenderTargetEvent& /*event*/)
{
  if (visibility_property_)
  {
    visibility_property_->update();
  }
  // Other camera-like displays may have set our scene node's bits; the frustum never shows in the
  // projector's own view.
  footprint_visual_->setVisibilityFlags(~vis_bit_);
  if (viewport_)
  {
    viewport_->setVisibilityMask(has_lens_ && pose_ok_ ? vis_bit_ : 0u);
  }
}

bool ProjectorCameraDisplay::FrameState::operator==(const FrameState& o) const
{
  return pose == o.pose && changes == o.changes && visibility == o.visibility && drawable == o.drawable &&
         std::equal(std::begin(viewport), std::end(viewport), std::begin(o.viewport));
}

void ProjectorCameraDisplay::markChanged()
{
  ++own_changes_;
}

bool ProjectorCameraDisplay::showsForeignDisplays() const
{
  if (!visibility_property_ || !visibility_property_->getBool())
  {
    return false;
  }
  // Same index mapping as onDisplayAdded(): one child per display of the group, except this one.
  rviz::DisplayGroup* group = context_->getRootDisplayGroup();
  int index = 0;
  for (int i = 0; i < group->numDisplays(); ++i)
  {
    rviz::Display* d = group->getDisplayAt(i);
    if (d == this)
    {
      continue;
    }
    rviz::Property* shown = index < visibility_property_->numChildren() ? visibility_property_->childAt(index) : nullptr;
    ++index;
    const bool ours = d->getClassId().startsWith("rviz_projector/");
    if (d->isEnabled() && shown && shown->getValue().toBool() && !ours)
    {
      return true;
    }
  }
  return false;
}

std::uint64_t ProjectorCameraDisplay::visibilitySignature() const
{
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over one byte per display
  auto mix = [&hash](std::uint8_t byte) {
    hash ^= byte;
    hash *= 1099511628211ull;
  };
  mix(visibility_property_ && visibility_property_->getBool() ? 1 : 0);
  rviz::DisplayGroup* group = context_->getRootDisplayGroup();
  for (int i = 0; i < group->numDisplays(); ++i)
  {
    mix(group->getDisplayAt(i)->isEnabled() ? 2 : 3);
  }
  for (int i = 0; visibility_property_ && i < visibility_property_->numChildren(); ++i)
  {
    mix(visibility_property_->childAt(i)->getValue().toBool() ? 4 : 5);
  }
  return hash;
}

bool ProjectorCameraDisplay::prepareFrame()
{
  if (!window_ || !viewport_)
  {
    return false;
  }
  pose_ok_ = has_lens_ && updateCameraPose();
  if (!has_lens_)
  {
    deleteStatus("Transform");
  }
  updateFootprint();
  updateViewport();
  return true;
}

void ProjectorCameraDisplay::drawFrame(bool swap)
{
  Ogre::RenderWindow* rw = window_->renderWindow();
  rw->update(false);
  ++frames_rendered_;
  if (swap)
  {
    rw->swapBuffers();
  }
}

void ProjectorCameraDisplay::renderNow()
{
  if (!isEnabled() || !window_ || !window_->isVisible())
  {
    return;
  }
  // rviz handles ROS callbacks (new paths, CameraInfo) only at its main view's frame rate; the
  // projector must not wait for that. Same thread as rviz's own spinOnce(), so this is safe.
  // Message-filter displays hand a message over through a queued Qt call (after their tf filter
  // passed it): deliver those too, so a new path is drawn in this frame, not the next.
  ros::spinOnce();
  QCoreApplication::sendPostedEvents(nullptr, QEvent::MetaCall);
  if (!prepareFrame())
  {
    return;
  }
  const bool publish = image_output_property_->getBool() && image_pub_ &&
                       (ros::WallTime::now() - last_image_time_).toSec() >= 1.0 / image_rate_property_->getFloat();

  FrameState state;
  const Ogre::Vector3& p = camera_node_->getPosition();
  const Ogre::Quaternion& q = camera_node_->getOrientation();
  state.pose = {p.x, p.y, p.z, q.w, q.x, q.y, q.z};
  state.changes = ProjectionChangeCounter::value() + own_changes_;
  state.visibility = visibilitySignature();
  viewportPixels(state.viewport[0], state.viewport[1], state.viewport[2], state.viewport[3]);
  state.drawable = has_lens_ && pose_ok_;
  if (have_last_frame_ && state == last_frame_ && !publish && !showsForeignDisplays())
  {
    ++frames_skipped_;  // the projector already shows exactly this
    return;
  }
  last_frame_ = state;
  have_last_frame_ = true;
  drawFrame(!publish);
  if (publish)
  {
    publishImage();
    window_->renderWindow()->swapBuffers();
  }
}

bool ProjectorCameraDisplay::grabFrame(std::vector<std::uint8_t>& rgb, unsigned& width, unsigned& height)
{
  if (!prepareFrame())
  {
    return false;
  }
  drawFrame(false);
  const bool ok = readRgbPixels(window_->renderWindow(), rgb, width, height);
  window_->renderWindow()->swapBuffers();
  return ok;
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

void ProjectorCameraDisplay::publishImage()
{
  last_image_time_ = ros::WallTime::now();
  int left, top, width, height;
  viewportPixels(left, top, width, height);
  unsigned ww = 0, wh = 0;
  if (!readRgbPixels(window_->renderWindow(), image_buffer_, ww, wh) || width <= 0 || height <= 0)
  {
    return;
  }
  sensor_msgs::Image image;
  image.header.stamp = ros::Time::now();
  image.header.frame_id = projectorFrame();
  image.width = static_cast<std::uint32_t>(width);
  image.height = static_cast<std::uint32_t>(height);
  image.encoding = "rgb8";
  image.step = image.width * 3;
  image.data.resize(static_cast<std::size_t>(image.step) * image.height);
  for (int row = 0; row < height; ++row)
  {
    const std::uint8_t* src = image_buffer_.data() + (static_cast<std::size_t>(row + top) * ww + left) * 3;
    std::copy(src, src + image.step, image.data.begin() + static_cast<std::ptrdiff_t>(row) * image.step);
  }
  image_pub_.publish(image);
  if (last_info_)
  {
    sensor_msgs::CameraInfo info = *last_info_;
    info.header = image.header;
    image_info_pub_.publish(info);
  }
}
}  // namespace rviz_projector

#include <pluginlib/class_list_macros.hpp>
PLUGINLIB_EXPORT_CLASS(rviz_projector::ProjectorCameraDisplay, rviz::Display)
