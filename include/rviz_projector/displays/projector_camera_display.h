// rviz display "rviz_projector/ProjectorCamera": renders the scene through the projector's lens
// (CameraInfo, pinhole model of P) from its pose (tf) straight into a full-screen window on the
// projector's screen. A thin adapter: PinholeModel does the maths, ProjectorOutputWindow the window.
#pragma once

#ifndef Q_MOC_RUN
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <OgreRenderTargetListener.h>
#include <QTimer>
#include <ros/ros.h>
#include <rviz/display.h>
#include <sensor_msgs/CameraInfo.h>

#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/vec2.h"
#endif

namespace Ogre
{
class Camera;
class SceneNode;
class Viewport;
}  // namespace Ogre
class QScreen;

namespace rviz
{
class BoolProperty;
class ColorProperty;
class DisplayGroupVisibilityProperty;
class EnumProperty;
class FloatProperty;
class IntProperty;
class RosTopicProperty;
class StringProperty;
}  // namespace rviz

namespace rviz_projector
{
class FloorMesh;
class ProjectorFootprintVisual;
class ProjectorOutputWindow;

class ProjectorCameraDisplay : public rviz::Display, public Ogre::RenderTargetListener
{
  Q_OBJECT
public:
  static constexpr const char* kDefaultTopic = "/projector/camera_info";
  static constexpr const char* kAutomaticScreen = "Automatic";

  ProjectorCameraDisplay();
  ~ProjectorCameraDisplay() override;

  void reset() override;
  /// Loads the config, then reports values that were clamped or replaced (a "Config" warning).
  void load(const rviz::Config& config) override;
  void setTopic(const QString& topic, const QString& datatype) override;
  /// Statuses are set every frame; these forward only actual changes to rviz (each call posts an
  /// event and repaints the Displays panel).
  void setStatus(rviz::StatusProperty::Level level, const QString& name, const QString& text) override;
  void deleteStatus(const QString& name) override;
  void clearStatuses() override;

  /// Frames skipped because nothing the projector shows had changed.
  std::uint64_t framesSkipped() const { return frames_skipped_; }
  /// Renders a frame and copies it (RGB, rows top down, whole window) before it is shown.
  bool grabFrame(std::vector<std::uint8_t>& rgb, unsigned& width, unsigned& height);
  /// The output window (nullptr while the display has never been enabled).
  ProjectorOutputWindow* outputWindow() const { return window_.get(); }
  /// The lens in use; valid() is false until a usable CameraInfo arrived.
  const PinholeModel& lens() const { return lens_; }
  bool hasLens() const { return has_lens_; }
  /// Viewport in window pixels (left, top, width, height) the image is drawn into.
  void viewportPixels(int& left, int& top, int& width, int& height) const;
  /// Frames rendered into the output window so far.
  std::uint64_t framesRendered() const { return frames_rendered_; }
  /// The visibility bit used by the projector view (0 when none could be allocated).
  std::uint32_t visibilityBit() const { return vis_bit_; }

protected:
  void onInitialize() override;
  void onEnable() override;
  void onDisable() override;
  void fixedFrameChanged() override;

  // Ogre::RenderTargetListener
  void preRenderTargetUpdate(const Ogre::RenderTargetEvent& event) override;

public Q_SLOTS:
  /// Renders the projector view now (the timer does this at the frame rate limit).
  void renderNow();

private Q_SLOTS:
  void updateTopic();
  void updateOutput();
  /// "Main view" warning when rviz's own view is known to starve this one (main_view_cost.h).
  void checkMainViewCost();
  void updateCameraSettings();
  void updateFrameRate();
  void onFootprintPropertyChanged();
  void updateTestPattern();
  void updateImageOutput();
  void fillScreenOptions();
  void onScreensChanged();
  void onLeaveFullScreenRequested();
  void onWindowClosed();
  void onDisplayAdded(rviz::Display* display);

private:
  void subscribe();
  void unsubscribe();
  void cameraInfoCallback(const sensor_msgs::CameraInfo::ConstPtr& msg);
  void applyCameraInfo();
  /// Full screen as the property asks, unless there is only one screen (never cover rviz).
  bool wantsFullScreen() const;
  /// Multisampling of the output window: 4x with Anti-aliasing, none without.
  int wantedFsaa() const;
  void createWindow();
  void destroyWindow();
  QScreen* chooseScreen(QString& why) const;
  /// Moves the camera to the projector's latest tf pose; false (with a status) when unavailable.
  bool updateCameraPose();
  void updateViewport();
  void updateFootprint();
  void publishImage();
  /// Follows tf and the window: camera pose, footprint, viewport. False when nothing can be drawn.
  bool prepareFrame();
  void updateFootprintVisible();
  /// Renders into the back buffer; `swap` shows it.
  void drawFrame(bool swap);
  /// Whether a display that is not from this package is shown in the projector view (its changes
  /// are not announced, so the view must render at its frame rate).
  bool showsForeignDisplays() const;
  /// Hash of the Visibility property's ticks and the displays' enabled states.
  std::uint64_t visibilitySignature() const;
  /// Something this display itself draws or how it draws changed: render again.
  void markChanged();
  std::string projectorFrame() const;
  void setDefaultVisibility(rviz::Property* visibility_child, rviz::Display* display);

  rviz::RosTopicProperty* topic_property_;
  rviz::StringProperty* frame_property_;
  rviz::EnumProperty* screen_property_;
  rviz::BoolProperty* full_screen_property_;
  rviz::ColorProperty* background_property_;
  rviz::FloatProperty* near_clip_property_;
  rviz::FloatProperty* far_clip_property_;
  rviz::IntProperty* frame_rate_property_;
  rviz::BoolProperty* anti_aliasing_property_;
  rviz::DisplayGroupVisibilityProperty* visibility_property_ = nullptr;
  rviz::BoolProperty* footprint_property_;
  rviz::BoolProperty* test_pattern_property_;
  rviz::BoolProperty* image_output_property_;
  rviz::StringProperty* image_topic_property_;
  rviz::FloatProperty* image_rate_property_;

  ros::Subscriber info_sub_;
  sensor_msgs::CameraInfo::ConstPtr last_info_;
  PinholeModel lens_;
  bool has_lens_ = false;
  bool pose_ok_ = false;
  std::string info_frame_;

  std::unique_ptr<ProjectorOutputWindow> window_;
  Ogre::Camera* camera_ = nullptr;
  Ogre::SceneNode* camera_node_ = nullptr;
  Ogre::Viewport* viewport_ = nullptr;
  std::uint32_t vis_bit_ = 0;
  QTimer render_timer_;
  std::uint64_t frames_rendered_ = 0;
  std::uint64_t frames_skipped_ = 0;

  /// What the last rendered frame depended on; an identical state needs no new frame.
  struct FrameState
  {
    std::array<float, 7> pose{};  // position, orientation (w, x, y, z)
    std::uint64_t changes = 0;    // ProjectionChangeCounter + own changes
    std::uint64_t visibility = 0;  // which displays the Visibility property shows
    int viewport[4] = {0, 0, 0, 0};
    bool drawable = false;
    bool operator==(const FrameState& o) const;
  };
  FrameState last_frame_;
  bool have_last_frame_ = false;
  std::uint64_t own_changes_ = 0;
  std::array<float, 7> footprint_key_{};  // camera pose the footprint was last computed for
  std::uint64_t footprint_changes_ = ~0ull;
  std::map<QString, std::pair<int, QString>> status_cache_;

  std::unique_ptr<ProjectorFootprintVisual> footprint_visual_;
  std::unique_ptr<FloorMesh> grid_mesh_;
  std::vector<Vec2> grid_triangles_;

  ros::Publisher image_pub_;
  ros::Publisher image_info_pub_;
  ros::WallTime last_image_time_;
  std::vector<std::uint8_t> image_buffer_;
};
}  // namespace rviz_projector
