// Reads a 32-bit render texture back strip by strip, top to bottom (issue 24: the distortion warp
// on a software renderer scans its ideal render for the cells with something on them). Each strip
// lands in one small buffer and goes to the caller while it is still in the CPU's cache: reading the
// whole 1382x864 picture out first, then scanning it, went through main memory twice.
// Two ways to read:
// - Direct: OpenGL 4.5's glGetTextureSubImage, in the texture's own byte order (RGBA, 8 bits): a
//   plain copy in Mesa's llvmpipe. Used with OGRE's OpenGL render system on OpenGL >= 4.5 for a
//   PF_BYTE_RGBA texture.
// - Whole: OGRE's blitToMemory of the whole texture (any render system), handed on in strips.
// RVIZ_PROJECTOR_WARP_READBACK=direct|whole|auto overrides the choice (auto: direct where it can).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <OgreTexture.h>

namespace rviz_projector
{
enum class RowReadback
{
  Whole,
  Direct
};

/// The choice (pure, for tests): `setting` is RVIZ_PROJECTOR_WARP_READBACK ("direct", "whole",
/// empty/"auto"); the render system's name (Ogre::RenderSystem::getName()), its OpenGL version, and
/// whether the texture is PF_BYTE_RGBA. Direct only where it can work (a "direct" setting on another
/// render system or an older OpenGL is refused: whole). `note` gets a message for an unknown setting
/// or a refused "direct".
RowReadback chooseRowReadback(const std::string& setting, const std::string& render_system, int gl_major,
                              int gl_minor, bool rgba8, std::string* note = nullptr);

class TextureRows
{
public:
  /// One strip: `count` rows from row `y0`, `stride` pixels apart (valid during the call only).
  using Strip = std::function<void(const std::uint32_t* rows, std::uint32_t y0, std::uint32_t count, std::size_t stride)>;

  /// Rows per strip: a multiple of the warp scan's 8-pixel blocks; 354 KB of 1382-pixel rows, in a
  /// core's L2 cache. Measured on llvmpipe (the same process, strips and whole reads alternating
  /// frame by frame): read + scan 0.25 ms with strips of 32 or 64 rows, 0.44-0.49 ms read whole
  /// in one call; 64 rows make half the driver calls (and allocations) of 32.
  static constexpr std::uint32_t kStripRows = 64;

  /// `texture`: a 32-bit texture that outlives this object. Chooses the way to read (above).
  explicit TextureRows(const Ogre::TexturePtr& texture);

  /// Hands every row of the texture to `strip`, top to bottom. False when a read failed: the strips
  /// handed on (if any) are then not the picture, and the direct read is not tried again. Under
  /// OpenGL a pixel-pack buffer left bound (by another part of the process) fails either read: the
  /// pixels would go into that buffer, not to the caller.
  bool read(const Strip& strip);

  RowReadback readback() const { return readback_; }
  /// A note on the choice for the status (empty when there is none).
  const std::string& note() const { return note_; }

private:
  bool readWhole(const Strip& strip);
  bool readDirect(const Strip& strip);

  Ogre::TexturePtr texture_;
  RowReadback readback_ = RowReadback::Whole;
  std::string note_;
  unsigned gl_id_ = 0;
  bool opengl_ = false;  // OGRE's OpenGL render system: its GL state can be asked
  const char* direct_failure_ = "";  // why the last direct read failed, for the note
  std::vector<std::uint32_t> buffer_;  // one strip (direct) or the whole picture (whole)
};
}  // namespace rviz_projector
