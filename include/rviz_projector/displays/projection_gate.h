// One part of ProjectorCameraDisplay: decides whether the projector view must render a new frame
// (what changed since the last one: pose, lens, scene, visibility, window), and keeps the Visibility
// ticks attached to the displays they belong to (by identity: moving a display in the Displays
// list, or removing one above it, never shifts ticks to other displays).
#pragma once

#ifndef Q_MOC_RUN
#include <array>
#include <cstdint>
#include <map>

#include <QElapsedTimer>
#include <QObject>

#include "rviz_projector/core/letterbox.h"
#include "rviz_projector/displays/render_policy.h"
#endif

namespace rviz
{
class Display;
class DisplayGroup;
class DisplayGroupVisibilityProperty;
class Property;
}  // namespace rviz

namespace rviz_projector
{
/// Everything a rendered projector frame depends on; an identical state needs no new frame.
struct FrameState
{
  std::array<float, 7> pose{};   ///< position, orientation (w, x, y, z)
  std::uint64_t changes = 0;     ///< ProjectionChangeCounter + the display's own changes
  std::uint64_t visibility = 0;  ///< ProjectionGate::visibilitySignature()
  PixelRect image;               ///< where the image is drawn in the window
  bool drawable = false;         ///< lens and pose available
  std::uint64_t foreign_scene = 0;  ///< host policy: ProjectionGate::foreignSceneSignature() (set by the gate)
  bool operator==(const FrameState& o) const;
};

class ProjectionGate : public QObject
{
  Q_OBJECT
public:
  /// Watches `group` (rviz's root display group) for `owner`. Create it before the Visibility
  /// property: it must hear a display's removal before the property forgets that display's tick.
  /// `policy` says how displays of other packages are judged (needsFrame()); the owner gives it (a
  /// display: the process's policy, the default).
  ProjectionGate(rviz::DisplayGroup* group, rviz::Display* owner,
                 const RenderPolicy& policy = processRenderPolicy());

  /// The owner's Visibility property, once created; existing displays get their default ticks.
  void attach(rviz::DisplayGroupVisibilityProperty* visibility);

  /// Whether `state` needs a new frame: it differs from the last frame rendered, or the view was
  /// invalidated, or the view shows displays that do not announce their changes (not from this
  /// package). Those force a frame every tick under rviz's policy; under projector_host's
  /// (RenderPolicy::host) only when their scene graph changed or its keep-alive period passed.
  /// When true, `state` is recorded as rendered.
  bool needsFrame(const FrameState& state);
  /// The next frame renders whatever the state (a new window, a read-back).
  void invalidate() { have_last_ = false; }

  /// Hash of the displays shown in the projector view (identity, enabled, tick); no allocation.
  std::uint64_t visibilitySignature() const;
  /// Hash of the scene graphs of the shown displays not from this package (scene_signature.h).
  std::uint64_t foreignSceneSignature() const;
  /// Whether a display not from this package is shown in the projector view.
  bool showsForeignDisplays() const;
  /// The Visibility tick of `display` (nullptr when it has none).
  rviz::Property* tickOf(const rviz::Display* display) const;
  /// Default tick of a new display: this package's displays are projected, others are not.
  static bool shownByDefault(const rviz::Display* display);

private Q_SLOTS:
  void onDisplayAdded(rviz::Display* display);
  void onDisplayRemoved(rviz::Display* display);
  void onDisplayDestroyed(QObject* display);

private:
  rviz::DisplayGroup* group_;
  rviz::Display* owner_;
  RenderPolicy policy_;
  rviz::DisplayGroupVisibilityProperty* visibility_ = nullptr;
  /// Ticks of displays taken out of the group: a display moved in the list comes back with its tick.
  std::map<const QObject*, bool> taken_out_;
  FrameState last_;
  bool have_last_ = false;
  QElapsedTimer since_last_frame_;
};
}  // namespace rviz_projector
