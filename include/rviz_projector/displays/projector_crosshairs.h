// One part of ProjectorCameraDisplay: the calibration crosshairs (Test pattern = Crosshairs) as the
// projector shows them. The core decides the pixels (crosshairPatternRects); this part turns the
// white rectangles into quads drawn in IMAGE space (identity view and projection, vertices in
// normalised device coordinates), so the pattern depends on the image size alone: not on the
// mount, tf or the scene.
//
// The quads live in a scene manager of their own, seen only by this part's camera: while the
// pattern is shown the projector's viewport uses that camera, so nothing of rviz's scene (and no
// floor grid) is drawn behind the pattern, and rviz's main view, which renders rviz's scene
// manager, can never show the pattern.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <OgreMaterial.h>

#include "rviz_projector/core/crosshair_pattern.h"

namespace Ogre
{
class Camera;
class ManualObject;
class SceneManager;
}  // namespace Ogre

namespace rviz_projector
{
/// Normalised device coordinates (OpenGL: x right, y up, both -1..1 across the viewport) of a pixel
/// edge: ROS pixel u is centred at window x = u + 0.5, so the edge x (pixel coordinates, e.g.
/// u - 0.5) is at window x + 0.5. Returns {x_left, y_bottom, x_right, y_top}.
std::array<double, 4> ndcOfPatternRect(const PatternRect& rect, std::uint32_t width, std::uint32_t height);

class ProjectorCrosshairs
{
public:
  ProjectorCrosshairs();
  ~ProjectorCrosshairs();
  ProjectorCrosshairs(const ProjectorCrosshairs&) = delete;
  ProjectorCrosshairs& operator=(const ProjectorCrosshairs&) = delete;

  /**
   * The pattern for an image of width x height pixels and rows x cols crosshairs. Rebuilds the quads
   * only when one of these changed; returns true when it did (the projector must render again).
   * `problem` gets why nothing is drawn ("" when the pattern is drawn).
   */
  bool update(std::uint32_t width, std::uint32_t height, int rows, int cols, std::string& problem);
  /// The camera the projector's viewport uses while the pattern is shown.
  Ogre::Camera* camera() const { return camera_; }
  /// The crosshairs drawn (empty when none).
  const std::vector<Crosshair>& pattern() const { return pattern_; }
  /// Number of quads drawn.
  std::size_t quadCount() const { return quads_; }

private:
  Ogre::SceneManager* scene_manager_;
  Ogre::Camera* camera_;
  Ogre::ManualObject* quads_object_;
  Ogre::MaterialPtr material_;
  std::array<long long, 4> key_{-1, -1, -1, -1};
  std::vector<Crosshair> pattern_;
  std::size_t quads_ = 0;
};
}  // namespace rviz_projector
