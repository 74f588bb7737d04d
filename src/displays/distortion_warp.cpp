#include "rviz_projector/displays/distortion_warp.h"

#include <cstdlib>

#include <OgreCamera.h>
#include <OgreHardwarePixelBuffer.h>
#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgrePass.h>
#include <OgrePixelFormat.h>
#include <OgreRenderSystem.h>
#include <OgreRenderSystemCapabilities.h>
#include <OgreRenderTexture.h>
#include <OgreResourceGroupManager.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneManagerEnumerator.h>
#include <OgreSceneNode.h>
#include <OgreTechnique.h>
#include <OgreTextureManager.h>
#include <OgreTextureUnitState.h>
#include <OgreViewport.h>

#include <ros/console.h>

#include "rviz_projector/displays/image_space.h"
#include "rviz_projector/displays/ogre_name.h"
#include "rviz_projector/displays/texture_rows.h"
#include "rviz_projector/displays/viewport_clear.h"
#include "rviz_projector/displays/warp_eraser.h"

namespace rviz_projector
{
namespace
{
/// The eraser is used while at most 1 / kEraseShare of the ideal render's blocks were lit.
constexpr std::size_t kEraseShare = 8;
}  // namespace

DistortionWarp::DistortionWarp(Ogre::Camera* scene_camera, Ogre::RenderTargetListener* listener)
  : scene_camera_(scene_camera)
  , listener_(listener)
  , warp_scene_(Ogre::Root::getSingleton().createSceneManager(Ogre::DefaultSceneManagerFactory::FACTORY_TYPE_NAME,
                                                              uniqueOgreName("rviz_projector_warp_scene_")))
  , warp_camera_(warp_scene_->createCamera(uniqueOgreName("rviz_projector_warp_camera_")))
  , mesh_(warp_scene_->createManualObject(uniqueOgreName("rviz_projector_warp_mesh_")))
{
  material_ = createImageSpaceMaterial("rviz_projector_warp_material_");
  useImageSpace(mesh_);
  mesh_->setDynamic(true);  // rewritten every frame when only occupied cells are drawn
  warp_scene_->getRootSceneNode()->attachObject(mesh_);
}

DistortionWarp::~DistortionWarp()
{
  clear();
  warp_scene_->getRootSceneNode()->detachAllObjects();
  warp_scene_->destroyManualObject(mesh_);
  warp_scene_->destroyCamera(warp_camera_);
  Ogre::Root::getSingleton().destroySceneManager(warp_scene_);
  Ogre::MaterialManager::getSingleton().remove(material_->getName(), material_->getGroup());
}

void DistortionWarp::clear()
{
  mesh_->clear();
  mesh_->setVisible(true);
  mesh_written_ = false;
  scan_.reset();
  rows_.reset();
  occupied_.clear();
  drawn_.clear();
  cells_ = WarpCells::All;
  cells_note_.clear();
  if (eraser_)
  {
    eraser_->attach(nullptr, 1, 1);  // its viewport goes with the texture's others below
  }
  erase_ready_ = false;
  lit_rects_.clear();
  if (render_texture_)
  {
    render_texture_->removeListener(listener_);
    render_texture_->removeAllViewports();
    render_texture_ = nullptr;
    viewport_ = nullptr;
  }
  if (texture_)
  {
    Ogre::Pass* pass = material_->getTechnique(0)->getPass(0);
    pass->removeAllTextureUnitStates();
    Ogre::TextureManager::getSingleton().remove(texture_->getName(), texture_->getGroup());
    texture_.reset();
  }
  grid_ = WarpGrid();
  grid_error_ = 0.0;
}

std::string DistortionWarp::configure(const PinholeModel& raw_lens, const LensDistortion& distortion)
{
  clear();
  if (distortion.none())
  {
    return std::string();
  }
  grid_ = makeWarpGrid(raw_lens, distortion);
  raw_width_ = raw_lens.width();
  raw_height_ = raw_lens.height();
  grid_error_ = warpGridError(grid_, raw_lens, distortion);
  const PinholeModel& ideal = grid_.ideal_lens;
  try
  {
    texture_ = Ogre::TextureManager::getSingleton().createManual(
        uniqueOgreName("rviz_projector_warp_texture_"), Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME,
        Ogre::TEX_TYPE_2D, ideal.width(), ideal.height(), 0, Ogre::PF_BYTE_RGBA, Ogre::TU_RENDERTARGET);
  }
  catch (const Ogre::Exception& e)
  {
    const std::string error = "the " + std::to_string(ideal.width()) + "x" + std::to_string(ideal.height()) +
                              " texture of the distortion warp could not be made: " + e.getDescription();
    clear();
    return error;
  }
  render_texture_ = texture_->getBuffer()->getRenderTarget();
  render_texture_->setAutoUpdated(false);
  render_texture_->addListener(listener_);
  viewport_ = render_texture_->addViewport(scene_camera_);
  viewport_->setOverlaysEnabled(false);
  setClearedBuffers(*viewport_, kProjectorClearBuffers);
  viewport_->setBackgroundColour(background_);
  viewport_->setVisibilityMask(visibility_mask_);

  Ogre::TextureUnitState* unit = material_->getTechnique(0)->getPass(0)->createTextureUnitState(texture_->getName());
  unit->setTextureAddressingMode(Ogre::TextureUnitState::TAM_CLAMP);
  unit->setTextureFiltering(Ogre::TFO_BILINEAR);
  unit->setNumMipmaps(0);

  const char* setting = std::getenv("RVIZ_PROJECTOR_WARP_CELLS");
  const Ogre::RenderSystem* render_system = Ogre::Root::getSingleton().getRenderSystem();
  const std::string renderer = render_system && render_system->getCapabilities() ?
                                   render_system->getCapabilities()->getDeviceName() :
                                   std::string();
  cells_ = chooseWarpCells(setting ? setting : "", renderer, &cells_note_);
  if (cells_ == WarpCells::Occupied && Ogre::PixelUtil::getNumElemBytes(texture_->getFormat()) != 4)
  {
    cells_ = WarpCells::All;  // the scan reads 32-bit pixels: any other texture draws every cell
  }
  if (cells_ == WarpCells::Occupied)
  {
    scan_ = std::make_unique<WarpCellScan>(grid_);
    rows_ = std::make_unique<TextureRows>(texture_);
    if (!eraser_)
    {
      eraser_ = std::make_unique<WarpEraser>();
    }
    eraser_->attach(render_texture_, ideal.width(), ideal.height());
  }
  writeMesh(nullptr);
  return std::string();
}

void DistortionWarp::writeMesh(const std::vector<std::uint8_t>* occupied)
{
  // The cells: raw pixel edges -> normalised device coordinates of the output viewport (which
  // holds the raw image exactly); each vertex samples the ideal render where its ray lands.
  const double raw_w = raw_width_;
  const double raw_h = raw_height_;
  if (mesh_written_)
  {
    mesh_->beginUpdate(0);
  }
  else
  {
    mesh_->estimateVertexCount(grid_.raw.size());
    mesh_->estimateIndexCount(6 * grid_.columns * grid_.rows);
    mesh_->begin(material_->getName(), Ogre::RenderOperation::OT_TRIANGLE_LIST,
                 Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
  }
  for (std::size_t v = 0; v < grid_.raw.size(); ++v)
  {
    const Vec2& p = grid_.raw[v];
    mesh_->position(static_cast<Ogre::Real>(2.0 * (p.x + 0.5) / raw_w - 1.0),
                    static_cast<Ogre::Real>(1.0 - 2.0 * (p.y + 0.5) / raw_h), 0.0f);
    const Vec2 t = grid_.textureCoordinate(v);
    mesh_->textureCoord(static_cast<Ogre::Real>(t.x), static_cast<Ogre::Real>(t.y));
  }
  for (std::uint32_t j = 0; j < grid_.rows; ++j)
  {
    for (std::uint32_t i = 0; i < grid_.columns; ++i)
    {
      if (occupied && !(*occupied)[std::size_t(j) * grid_.columns + i])
      {
        continue;
      }
      const auto a = static_cast<Ogre::uint32>(grid_.vertexIndex(i, j));
      const auto b = static_cast<Ogre::uint32>(grid_.vertexIndex(i + 1, j));
      const auto c = static_cast<Ogre::uint32>(grid_.vertexIndex(i, j + 1));
      const auto d = static_cast<Ogre::uint32>(grid_.vertexIndex(i + 1, j + 1));
      mesh_->triangle(a, b, c);  // the split of core warpGridError
      mesh_->triangle(b, d, c);
    }
  }
  mesh_->end();
  if (!mesh_written_)
  {
    mesh_->setBoundingBox(Ogre::AxisAlignedBox::BOX_INFINITE);  // in image space: never culled
  }
  mesh_written_ = true;
}

std::string DistortionWarp::cellsNote() const
{
  const std::string rows = rows_ ? rows_->note() : std::string();
  return cells_note_.empty() ? rows : rows.empty() ? cells_note_ : cells_note_ + "; " + rows;
}

bool DistortionWarp::readsDirectly() const
{
  return rows_ && rows_->readback() == RowReadback::Direct;
}

void DistortionWarp::drawOccupiedCells()
{
  const Ogre::PixelFormat format = texture_->getFormat();  // 32-bit (configure())
  // The background as the clear leaves it and the colour bits, in the texture's own layout (alpha
  // is not shown).
  std::uint32_t background = 0;
  std::uint32_t colour_bits = 0;
  const std::array<std::uint8_t, 4>& b = background_bytes_;
  Ogre::PixelUtil::packColour(b[0], b[1], b[2], b[3], format, &background);
  Ogre::PixelUtil::packColour(Ogre::uint8(255), Ogre::uint8(255), Ogre::uint8(255), Ogre::uint8(0), format,
                              &colour_bits);
  // Strip by strip: each is scanned while it is in the cache. A failed read leaves rows out, and
  // a scan that misses rows draws every cell (never drops one).
  scan_->begin(background, colour_bits);
  if (!rows_->read([this](const std::uint32_t* rows, std::uint32_t y0, std::uint32_t count, std::size_t stride) {
        scan_->addRows(rows, y0, count, stride);
      }))
  {
    ROS_WARN_STREAM_THROTTLE(5.0, "rviz_projector: " << (rows_->note().empty() ?
                                                             "the ideal render could not be read back" :
                                                             rows_->note())
                                                      << "; every cell of the warp is drawn this frame");
  }
  const std::size_t count = scan_->finish(occupied_);
  // The texture now holds the scan's picture in the current background: the next frame erases what
  // the scan found lit (prepareTexture; a picture not read back whole: it clears all of it).
  erase_ready_ = true;
  mesh_->setVisible(count > 0);
  if (count > 0 && occupied_ != drawn_)  // the same cells as the last frame: the mesh holds them
  {
    writeMesh(&occupied_);
    drawn_ = occupied_;
  }
}

void DistortionWarp::prepareTexture()
{
  // A clear fills every pixel (0.6-0.7 ms for 1382x864 on llvmpipe); painting shades each quad's
  // pixels, which costs more per pixel: it pays while little is lit. Past an eighth of the blocks
  // lit (chosen, not tuned) the texture is cleared whole, as it is after a failed read, a new
  // texture or another background (erase_ready_ false).
  const bool erase = erase_ready_ && scan_->complete() && scan_->litBlocks() * kEraseShare <= scan_->blocks();
  lit_rects_.clear();
  if (erase)
  {
    scan_->litRects(lit_rects_);
  }
  eraser_->paint(lit_rects_, background_bytes_);
  setClearedBuffers(*viewport_, erase ? kErasedTextureClearBuffers : kProjectorClearBuffers);
}

void DistortionWarp::setBackground(const Ogre::ColourValue& colour)
{
  if (colour != background_)
  {
    erase_ready_ = false;  // the texture holds the old background: cleared whole next frame
  }
  background_ = colour;
  background_bytes_ = clearedBytes(colour.r, colour.g, colour.b, colour.a);
  if (viewport_)
  {
    viewport_->setBackgroundColour(colour);
  }
}

void DistortionWarp::setVisibilityMask(std::uint32_t mask)
{
  visibility_mask_ = mask;
  if (viewport_)
  {
    viewport_->setVisibilityMask(mask);
  }
}

void DistortionWarp::renderIdeal()
{
  if (render_texture_)
  {
    if (cells_ == WarpCells::Occupied)
    {
      prepareTexture();
    }
    render_texture_->update(false);
    if (cells_ == WarpCells::Occupied)
    {
      drawOccupiedCells();
    }
  }
}
}  // namespace rviz_projector
