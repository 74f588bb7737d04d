#include "rviz_projector/displays/texture_rows.h"

#include <algorithm>
#include <cstdlib>

#include <GL/gl.h>
#include <GL/glx.h>

#include <OgreException.h>
#include <OgreHardwarePixelBuffer.h>
#include <OgrePixelFormat.h>
#include <OgreRenderSystem.h>
#include <OgreRenderSystemCapabilities.h>
#include <OgreRoot.h>

#include "rviz_projector/core/ascii_lower.h"

namespace rviz_projector
{
namespace
{
// OpenGL 4.5 (ARB_get_texture_sub_image); looked up at run time, as any GL entry point past 1.x.
using GetTextureSubImage = void (*)(GLuint texture, GLint level, GLint xoffset, GLint yoffset, GLint zoffset,
                                    GLsizei width, GLsizei height, GLsizei depth, GLenum format, GLenum type,
                                    GLsizei buf_size, void* pixels);

GetTextureSubImage getTextureSubImage()
{
  static const auto function = reinterpret_cast<GetTextureSubImage>(
      glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glGetTextureSubImage")));
  return function;
}

// OGRE's OpenGL render system (its GL state can be asked; the direct read needs it).
bool isOpenGL(const std::string& render_system)
{
  return asciiLower(render_system).find("opengl") != std::string::npos;
}

// The pixel-pack buffer bound now (0: none): a read would go into it, not into client memory.
GLint boundPackBuffer()
{
  GLint buffer = 0;
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &buffer);
  return buffer;
}

// The pack state glGetTextureSubImage reads, set to tight rows into client memory and put back
// afterwards (OGRE keeps its own view of the GL state).
class PackState
{
public:
  PackState()
  {
    buffer_ = boundPackBuffer();
    glGetIntegerv(GL_PACK_ROW_LENGTH, &row_length_);
    glGetIntegerv(GL_PACK_SKIP_ROWS, &skip_rows_);
    glGetIntegerv(GL_PACK_SKIP_PIXELS, &skip_pixels_);
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment_);
    glGetIntegerv(GL_PACK_SWAP_BYTES, &swap_bytes_);
    glPixelStorei(GL_PACK_ROW_LENGTH, 0);
    glPixelStorei(GL_PACK_SKIP_ROWS, 0);
    glPixelStorei(GL_PACK_SKIP_PIXELS, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glPixelStorei(GL_PACK_SWAP_BYTES, GL_FALSE);
  }
  ~PackState()
  {
    glPixelStorei(GL_PACK_ROW_LENGTH, row_length_);
    glPixelStorei(GL_PACK_SKIP_ROWS, skip_rows_);
    glPixelStorei(GL_PACK_SKIP_PIXELS, skip_pixels_);
    glPixelStorei(GL_PACK_ALIGNMENT, alignment_);
    glPixelStorei(GL_PACK_SWAP_BYTES, swap_bytes_);
  }
  PackState(const PackState&) = delete;
  PackState& operator=(const PackState&) = delete;
  /// A pixel pack buffer is bound: the read would go into it, not into client memory.
  bool packBufferBound() const { return buffer_ != 0; }

private:
  GLint buffer_ = 0, row_length_ = 0, skip_rows_ = 0, skip_pixels_ = 0, alignment_ = 4, swap_bytes_ = 0;
};
}  // namespace

RowReadback chooseRowReadback(const std::string& setting, const std::string& render_system, int gl_major,
                              int gl_minor, bool rgba8, std::string* note)
{
  const std::string s = asciiLower(setting);
  const bool possible = isOpenGL(render_system) &&
                        (gl_major > 4 || (gl_major == 4 && gl_minor >= 5)) && rgba8;
  if (s == "whole")
  {
    return RowReadback::Whole;
  }
  if (!s.empty() && s != "auto" && s != "direct" && note)
  {
    *note = "RVIZ_PROJECTOR_WARP_READBACK='" + setting + "' is not one of direct, whole, auto: auto is used";
  }
  if (s == "direct" && !possible && note)
  {
    *note = "RVIZ_PROJECTOR_WARP_READBACK=direct needs OpenGL 4.5 (" + render_system + ", OpenGL " +
            std::to_string(gl_major) + "." + std::to_string(gl_minor) + ") and an RGBA texture: whole is used";
  }
  return possible ? RowReadback::Direct : RowReadback::Whole;
}

TextureRows::TextureRows(const Ogre::TexturePtr& texture) : texture_(texture)
{
  const Ogre::RenderSystem* render_system = Ogre::Root::getSingleton().getRenderSystem();
  const Ogre::RenderSystemCapabilities* caps = render_system ? render_system->getCapabilities() : nullptr;
  const Ogre::DriverVersion version = caps ? caps->getDriverVersion() : Ogre::DriverVersion();
  const char* setting = std::getenv("RVIZ_PROJECTOR_WARP_READBACK");
  const std::string name = render_system ? render_system->getName() : std::string();
  opengl_ = isOpenGL(name);
  readback_ = chooseRowReadback(setting ? setting : "", name, version.major, version.minor,
                                texture_->getFormat() == Ogre::PF_BYTE_RGBA, &note_);
  if (readback_ == RowReadback::Direct)
  {
    try
    {
      texture_->getCustomAttribute("GLID", &gl_id_);
    }
    catch (const Ogre::Exception&)
    {
      gl_id_ = 0;
    }
    if (gl_id_ == 0 || getTextureSubImage() == nullptr)
    {
      readback_ = RowReadback::Whole;
    }
  }
}

bool TextureRows::read(const Strip& strip)
{
  if (readback_ == RowReadback::Direct)
  {
    if (readDirect(strip))
    {
      return true;
    }
    readback_ = RowReadback::Whole;  // never again: this frame's cells are all drawn
    note_ = std::string("the direct read of the ideal render failed (") + direct_failure_ +
            "): read whole from now on";
    return false;
  }
  return readWhole(strip);
}

bool TextureRows::readWhole(const Strip& strip)
{
  const std::uint32_t w = texture_->getWidth();
  const std::uint32_t h = texture_->getHeight();
  if (opengl_ && boundPackBuffer() != 0)
  {
    return false;  // OGRE's glGetTexImage would write into that buffer, leaving buffer_ as it was
  }
  buffer_.resize(std::size_t(w) * h);
  try
  {
    texture_->getBuffer()->blitToMemory(Ogre::PixelBox(w, h, 1, texture_->getFormat(), buffer_.data()));
  }
  catch (const Ogre::Exception&)
  {
    return false;
  }
  for (std::uint32_t y = 0; y < h; y += kStripRows)
  {
    strip(buffer_.data() + std::size_t(y) * w, y, std::min(kStripRows, h - y), w);
  }
  return true;
}

bool TextureRows::readDirect(const Strip& strip)
{
  const std::uint32_t w = texture_->getWidth();
  const std::uint32_t h = texture_->getHeight();
  buffer_.resize(std::size_t(w) * kStripRows);
  const PackState pack;
  if (pack.packBufferBound())
  {
    direct_failure_ = "a pixel-pack buffer was bound";
    return false;
  }
  direct_failure_ = "OpenGL error";
  for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; ++i)
  {
    // Errors of earlier calls (OGRE does not read them): not ours to judge.
  }
  const GetTextureSubImage get = getTextureSubImage();
  for (std::uint32_t y = 0; y < h; y += kStripRows)
  {
    const std::uint32_t rows = std::min(kStripRows, h - y);
    get(gl_id_, 0, 0, GLint(y), 0, GLsizei(w), GLsizei(rows), 1, GL_RGBA, GL_UNSIGNED_BYTE,
        GLsizei(std::size_t(w) * rows * sizeof(std::uint32_t)), buffer_.data());
    if (glGetError() != GL_NO_ERROR)
    {
      return false;
    }
    strip(buffer_.data(), y, rows, w);
  }
  return true;
}
}  // namespace rviz_projector
