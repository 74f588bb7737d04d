// One part of ProjectorCameraDisplay (issue 24): drawing through a distorting lens. The scene is
// rendered by the projector's camera as the ideal pinhole of a WarpGrid (core) into a texture,
// and a mesh of the grid's cells, in a scene of its own, draws that texture into the output
// window where each raw pixel's ray lands. With no distortion nothing here exists (no texture, no
// extra pass): the projector's camera draws into the window as before.
// On a software renderer the mesh costs ~12 ns of CPU per window pixel whatever the pixel shows
// (~11 ms per 1280x800 frame on llvmpipe): there the ideal render is read back and only the cells
// with something on them are drawn, into a window cleared to the background (core warp_cells.h;
// RVIZ_PROJECTOR_WARP_CELLS=all|occupied|auto overrides the choice). The read-back goes strip by
// strip into the scan (texture_rows.h); what it finds lit is all the next frame puts back to the
// background in the texture, instead of clearing all of it (warp_eraser.h).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <OgreColourValue.h>
#include <OgreMaterial.h>
#include <OgreTexture.h>

#include "rviz_projector/core/lens_distortion.h"
#include "rviz_projector/core/pinhole_model.h"
#include "rviz_projector/core/warp_cells.h"
#include "rviz_projector/core/warp_grid.h"

namespace Ogre
{
class Camera;
class ManualObject;
class RenderTargetListener;
class RenderTexture;
class SceneManager;
class Viewport;
}  // namespace Ogre

namespace rviz_projector
{
class TextureRows;
class WarpEraser;

class DistortionWarp
{
public:
  /// `scene_camera` renders the ideal view into the texture; `listener` hears that render (it
  /// refreshes the visibility bits before it, as for the window). Both outlive this object.
  DistortionWarp(Ogre::Camera* scene_camera, Ogre::RenderTargetListener* listener);
  ~DistortionWarp();
  DistortionWarp(const DistortionWarp&) = delete;
  DistortionWarp& operator=(const DistortionWarp&) = delete;

  /// For a raw lens (K's pinhole of the projector's pixels) and its distortion: none -> off (all
  /// released). Returns an error text when the texture cannot be made (the warp is then off).
  std::string configure(const PinholeModel& raw_lens, const LensDistortion& distortion);
  /// Releases everything: no distortion.
  void clear();

  bool active() const { return render_texture_ != nullptr; }
  /// The pinhole the scene camera must render with while active (the grid's ideal lens).
  const PinholeModel& idealLens() const { return grid_.ideal_lens; }
  const WarpGrid& grid() const { return grid_; }
  /// Largest interpolation error of the grid, raw pixels (core warpGridError).
  double gridError() const { return grid_error_; }
  /// The camera that draws the warped picture (into the output window's viewport).
  Ogre::Camera* warpCamera() const { return warp_camera_; }
  /// Every cell or only those with something on them (chosen in configure(): only those on a
  /// software renderer, when the texture's pixels are 32-bit).
  WarpCells cells() const { return cells_; }
  /// Occupied cells: the ideal render is read back straight from OpenGL strip by strip (true) or
  /// through OGRE whole (false; texture_rows.h).
  bool readsDirectly() const;
  /// The mesh draws every pixel of the window (the window need not be cleared before it).
  bool coversWindow() const { return active() && cells_ == WarpCells::All; }
  /// A note on the choice of cells for the status (e.g. an unknown RVIZ_PROJECTOR_WARP_CELLS), and
  /// the reader's on how the render is read back (e.g. a direct read that failed).
  std::string cellsNote() const;

  void setBackground(const Ogre::ColourValue& colour);
  void setVisibilityMask(std::uint32_t mask);
  /// Renders the ideal view into the texture (before the window's render).
  void renderIdeal();

private:
  /// (Re)writes the mesh: every vertex, the triangles of the cells `occupied` marks (all: null).
  void writeMesh(const std::vector<std::uint8_t>* occupied);
  /// Occupied cells only: reads the ideal render back and draws the cells with something on them.
  void drawOccupiedCells();
  /// Occupied cells only, before the ideal render: erase what the last frame lit, or clear it all.
  void prepareTexture();

  Ogre::Camera* scene_camera_;
  Ogre::RenderTargetListener* listener_;
  Ogre::SceneManager* warp_scene_;
  Ogre::Camera* warp_camera_;
  Ogre::ManualObject* mesh_;
  Ogre::MaterialPtr material_;
  Ogre::TexturePtr texture_;
  Ogre::RenderTexture* render_texture_ = nullptr;
  Ogre::Viewport* viewport_ = nullptr;
  Ogre::ColourValue background_ = Ogre::ColourValue::Black;
  std::uint32_t visibility_mask_ = 0xFFFFFFFFu;
  WarpGrid grid_;
  double grid_error_ = 0.0;
  WarpCells cells_ = WarpCells::All;
  std::string cells_note_;
  std::unique_ptr<WarpCellScan> scan_;
  std::unique_ptr<TextureRows> rows_;   // reads the ideal render back (occupied cells only)
  std::vector<std::uint8_t> occupied_;  // per cell
  std::vector<std::uint8_t> drawn_;     // the cells the mesh holds (empty: every cell, or none yet)
  // Occupied cells: the texture's colour is put back where the last frame lit it (warp_eraser.h)
  // instead of cleared whole, when that frame's picture was read back whole and lit little of it.
  std::unique_ptr<WarpEraser> eraser_;
  std::vector<TexelRect> lit_rects_;  // scratch: what prepareTexture() has the eraser paint
  bool erase_ready_ = false;  // the texture holds scan_'s last picture in the current background
  std::array<std::uint8_t, 4> background_bytes_{{0, 0, 0, 255}};  // the texture's bytes after a clear
  bool mesh_written_ = false;
  std::uint32_t raw_width_ = 1, raw_height_ = 1;  // the raw image the mesh spans
};
}  // namespace rviz_projector
