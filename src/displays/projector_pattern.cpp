#include "rviz_projector/displays/projector_pattern.h"

#include <algorithm>

#include <OgreCamera.h>
#include <OgreHardwarePixelBuffer.h>
#include <OgreManualObject.h>
#include <OgreMaterialManager.h>
#include <OgrePass.h>
#include <OgreResourceGroupManager.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreSceneManagerEnumerator.h>
#include <OgreSceneNode.h>
#include <OgreTechnique.h>
#include <OgreTextureManager.h>
#include <OgreTextureUnitState.h>
#include <sensor_msgs/image_encodings.h>

#include "rviz_projector/displays/image_space.h"
#include "rviz_projector/displays/ogre_name.h"

namespace rviz_projector
{
namespace
{
/// Byte offsets of blue, green, red and alpha (-1: none) in one pixel of `encoding`, and its size.
struct Layout
{
  int size = 0;
  int b = 0, g = 0, r = 0, a = -1;
};

bool layoutOf(const std::string& encoding, Layout& out)
{
  namespace enc = sensor_msgs::image_encodings;
  if (encoding == enc::MONO8)
    out = Layout{1, 0, 0, 0, -1};
  else if (encoding == enc::RGB8)
    out = Layout{3, 2, 1, 0, -1};
  else if (encoding == enc::BGR8)
    out = Layout{3, 0, 1, 2, -1};
  else if (encoding == enc::RGBA8)
    out = Layout{4, 2, 1, 0, 3};
  else if (encoding == enc::BGRA8)
    out = Layout{4, 0, 1, 2, 3};
  else
    return false;
  return true;
}
}  // namespace

std::string patternPixels(const sensor_msgs::Image& image, std::uint32_t width, std::uint32_t height,
                          std::vector<std::uint8_t>& bgra)
{
  Layout layout;
  if (!layoutOf(image.encoding, layout))
  {
    return "encoding '" + image.encoding + "' is not shown (mono8, rgb8, bgr8, rgba8 or bgra8)";
  }
  if (image.width != width || image.height != height)
  {
    return std::to_string(image.width) + "x" + std::to_string(image.height) + " is not the projector's image (" +
           std::to_string(width) + "x" + std::to_string(height) + "): a pattern is shown 1:1, never scaled";
  }
  const std::uint64_t row = static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(layout.size);
  if (image.step < row)
  {
    return "step " + std::to_string(image.step) + " is shorter than a row (" + std::to_string(row) + " bytes)";
  }
  if (static_cast<std::uint64_t>(image.data.size()) < static_cast<std::uint64_t>(image.step) * height)
  {
    return "data holds " + std::to_string(image.data.size()) + " bytes, height x step needs " +
           std::to_string(static_cast<std::uint64_t>(image.step) * height);
  }
  bgra.resize(static_cast<std::size_t>(width) * height * 4);
  for (std::uint32_t v = 0; v < height; ++v)
  {
    const std::uint8_t* in = image.data.data() + static_cast<std::size_t>(v) * image.step;
    std::uint8_t* out = bgra.data() + static_cast<std::size_t>(v) * width * 4;
    for (std::uint32_t u = 0; u < width; ++u, in += layout.size, out += 4)
    {
      out[0] = in[layout.b];
      out[1] = in[layout.g];
      out[2] = in[layout.r];
      out[3] = layout.a < 0 ? 255 : in[layout.a];
    }
  }
  return std::string();
}

ProjectorPattern::ProjectorPattern()
  : scene_manager_(Ogre::Root::getSingleton().createSceneManager(Ogre::DefaultSceneManagerFactory::FACTORY_TYPE_NAME,
                                                                 uniqueOgreName("rviz_projector_pattern_scene_")))
  , camera_(scene_manager_->createCamera(uniqueOgreName("rviz_projector_pattern_camera_")))
  , quad_(scene_manager_->createManualObject(uniqueOgreName("rviz_projector_pattern_quad_")))
{
  queue_.attach(nh_);
  material_ = createImageSpaceMaterial("rviz_projector_pattern_material_");
  useImageSpace(quad_);
  scene_manager_->getRootSceneNode()->attachObject(quad_);
}

ProjectorPattern::~ProjectorPattern()
{
  unsubscribe();
  scene_manager_->getRootSceneNode()->detachAllObjects();
  scene_manager_->destroyManualObject(quad_);
  scene_manager_->destroyCamera(camera_);
  Ogre::Root::getSingleton().destroySceneManager(scene_manager_);
  if (texture_)
  {
    Ogre::TextureManager::getSingleton().remove(texture_->getName(), texture_->getGroup());
  }
  Ogre::MaterialManager::getSingleton().remove(material_->getName(), material_->getGroup());
}

std::string ProjectorPattern::subscribe(const std::string& topic)
{
  unsubscribe();
  topic_ = topic;
  if (topic.empty())
  {
    return std::string();
  }
  try
  {
    sub_ = nh_.subscribe(topic, 1, &ProjectorPattern::callback, this);
    shown_pub_ = nh_.advertise<std_msgs::Header>(topic + "/shown", 10);
  }
  catch (const ros::Exception& e)
  {
    sub_.shutdown();
    setStatus(Level::Error, std::string("Error subscribing: ") + e.what());
    return e.what();
  }
  return std::string();
}

void ProjectorPattern::unsubscribe()
{
  sub_.shutdown();
  shown_pub_.shutdown();
  pending_.reset();
  shown_ = false;
  ack_due_ = false;
  received_ = 0;
  acknowledged_ = 0;
  setStatus(Level::None, std::string());
}

void ProjectorPattern::callback(const sensor_msgs::Image::ConstPtr& msg)
{
  ++received_;
  pending_ = msg;  // newest wins
}

bool ProjectorPattern::poll(std::uint32_t width, std::uint32_t height, double timeout_seconds, SteadyTime now)
{
  queue_.drain();
  bool changed = false;
  if (pending_ && width > 0 && height > 0)
  {
    const sensor_msgs::Image::ConstPtr msg = std::move(pending_);
    pending_.reset();
    if (msg->width == 0 && msg->height == 0)
    {
      changed = shown_;
      shown_ = false;
      ack_ = msg->header;
      ack_due_ = true;
      setStatus(Level::None, std::string());
    }
    else
    {
      std::vector<std::uint8_t> bgra;
      const std::string error = patternPixels(*msg, width, height, bgra);
      if (!error.empty())
      {
        changed = shown_;
        end("Not shown: " + error, Level::Error);
      }
      else
      {
        upload(bgra, width, height);
        shown_ = true;
        changed = true;
        ack_ = msg->header;
        ack_due_ = true;
        last_pattern_ = now;
        setStatus(Level::Ok, "Showing '" + msg->header.frame_id + "' (" + msg->encoding + ", 1:1) from " + topic_ +
                                 " instead of the scene");
      }
    }
  }
  if (shown_ && (texture_->getWidth() != width || texture_->getHeight() != height))
  {
    changed = true;
    end("Ended: the projector's image became " + std::to_string(width) + "x" + std::to_string(height), Level::Warn);
  }
  else if (shown_ && timeout_seconds > 0.0 &&
           std::chrono::duration<double>(now - last_pattern_).count() > timeout_seconds)
  {
    changed = true;
    std::string seconds = std::to_string(timeout_seconds);
    seconds.erase(seconds.find_last_not_of('0') + 1);
    if (!seconds.empty() && seconds.back() == '.')
      seconds.pop_back();
    end("Ended: no pattern for " + seconds + " s (Pattern timeout): showing the scene again", Level::Warn);
  }
  return changed;
}

void ProjectorPattern::refuse(const std::string& why)
{
  end(why, Level::Error);
}

void ProjectorPattern::end(const std::string& why, Level level)
{
  shown_ = false;
  ack_due_ = false;
  setStatus(level, why);
}

void ProjectorPattern::frameShown()
{
  if (ack_due_ && shown_pub_)
  {
    shown_pub_.publish(ack_);
    ++acknowledged_;
  }
  ack_due_ = false;
}

void ProjectorPattern::upload(const std::vector<std::uint8_t>& bgra, std::uint32_t width, std::uint32_t height)
{
  if (!texture_ || texture_->getWidth() != width || texture_->getHeight() != height)
  {
    Ogre::Pass* pass = material_->getTechnique(0)->getPass(0);
    pass->removeAllTextureUnitStates();
    if (texture_)
    {
      Ogre::TextureManager::getSingleton().remove(texture_->getName(), texture_->getGroup());
    }
    texture_ = Ogre::TextureManager::getSingleton().createManual(
        uniqueOgreName("rviz_projector_pattern_texture_"), Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME,
        Ogre::TEX_TYPE_2D, width, height, 0, Ogre::PF_BYTE_BGRA, Ogre::TU_DYNAMIC_WRITE_ONLY_DISCARDABLE);
    Ogre::TextureUnitState* unit = pass->createTextureUnitState(texture_->getName());
    unit->setTextureAddressingMode(Ogre::TextureUnitState::TAM_CLAMP);
    unit->setTextureFiltering(Ogre::TFO_NONE);  // 1:1: every pixel exactly its texel, never blended
    unit->setNumMipmaps(0);
    // One quad over the whole viewport (which holds the projector's image exactly): texture row 0
    // at the top.
    quad_->clear();
    quad_->begin(material_->getName(), Ogre::RenderOperation::OT_TRIANGLE_LIST,
                 Ogre::ResourceGroupManager::DEFAULT_RESOURCE_GROUP_NAME);
    const auto corner = [this](float x, float y, float s, float t) {
      quad_->position(x, y, 0.0f);
      quad_->textureCoord(s, t);
    };
    corner(-1.0f, -1.0f, 0.0f, 1.0f);
    corner(1.0f, -1.0f, 1.0f, 1.0f);
    corner(1.0f, 1.0f, 1.0f, 0.0f);
    corner(-1.0f, 1.0f, 0.0f, 0.0f);
    quad_->quad(0, 1, 2, 3);
    quad_->end();
    quad_->setBoundingBox(Ogre::AxisAlignedBox::BOX_INFINITE);  // in image space: never culled
  }
  // PixelBox takes a non-const pointer; blitFromMemory only reads it.
  texture_->getBuffer()->blitFromMemory(
      Ogre::PixelBox(width, height, 1, Ogre::PF_BYTE_BGRA, const_cast<std::uint8_t*>(bgra.data())));
}

void ProjectorPattern::setStatus(Level level, const std::string& text)
{
  if (level != level_ || text != status_)
  {
    level_ = level;
    status_ = text;
    status_changed_ = true;
  }
}

bool ProjectorPattern::takeStatusChange()
{
  const bool changed = status_changed_;
  status_changed_ = false;
  return changed;
}
}  // namespace rviz_projector
