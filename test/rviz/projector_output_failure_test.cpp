// Issue 11, defect 7: the output window's render window cannot be created. OGRE throws from
// Root::createRenderWindow when a render target of the same name already exists (as for a GL
// error or exhausted resources, an Ogre::Exception): the test takes the names the next output
// windows will get (ogre_name.h's process-wide counter) with render targets that only hold a name,
// then asks for a new output window. Required: an Error status "Output" that says so, rviz keeps
// running, and a later setting, once the names are free again, brings the projector back.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include <OgreRenderSystem.h>
#include <OgreRenderTarget.h>
#include <OgreRoot.h>
#include <QApplication>
#include <rviz/display.h>

#include "rviz_projector/displays/ogre_name.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "projector_test_fixture.h"

using rviz_projector_test::countColour;
using rviz_projector_test::kArrowMagenta;
using rviz_projector_test::ProjectorSceneTest;
using rviz_projector_test::Status;

namespace
{
/// A render target that holds only its name in OGRE's render system (never active, never drawn).
class NameHolder : public Ogre::RenderTarget
{
public:
  explicit NameHolder(const std::string& name)
  {
    mName = name;
    mWidth = mHeight = 1;
    mActive = false;
    mAutoUpdate = false;
  }
  void copyContentsToMemory(const Ogre::Box& /*src*/, const Ogre::PixelBox& /*dst*/, FrameBuffer /*buffer*/) override
  {
  }
  bool requiresTextureFlipping() const override { return false; }
};

/// Holds the names the next `count` output windows would get; frees them when destroyed.
class TakenWindowNames
{
public:
  explicit TakenWindowNames(int count)
  {
    // The counter is shared by every OGRE name of the package: reading one name tells the next.
    const std::string probe = rviz_projector::uniqueOgreName("rviz_projector_window_");
    const unsigned next = static_cast<unsigned>(std::stoul(probe.substr(probe.find_last_not_of("0123456789") + 1))) + 1;
    for (int i = 0; i < count; ++i)
    {
      holders_.push_back(std::make_unique<NameHolder>("rviz_projector_window_" + std::to_string(next + i)));
      Ogre::Root::getSingleton().getRenderSystem()->attachRenderTarget(*holders_.back());
    }
  }
  ~TakenWindowNames()
  {
    for (const auto& holder : holders_)
    {
      Ogre::Root::getSingleton().getRenderSystem()->detachRenderTarget(holder->getName());
    }
  }

private:
  std::vector<std::unique_ptr<NameHolder>> holders_;
};

int visibleProjectorWindows()
{
  int n = 0;
  for (QWidget* w : QApplication::topLevelWidgets())
  {
    n += qobject_cast<rviz_projector::ProjectorOutputWindow*>(w) && w->isVisible() ? 1 : 0;
  }
  return n;
}
}  // namespace

TEST_F(ProjectorSceneTest, OutputWindowThatCannotBeCreatedIsAnErrorAndALaterSettingRecovers)
{
  addPath("/test/plan", { { 0.5, 0.0 }, { 2.0, 0.0 } });
  ASSERT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100) << "the projector works before";
  {
    const TakenWindowNames taken(8);
    // Multisampling is fixed per native window: turning it on needs a new output window.
    projector_->subProp("Anti-aliasing")->setValue(true);
    const Status output = statusOf(projector_, "Output");
    ASSERT_TRUE(output.present);
    EXPECT_EQ(output.level, rviz::StatusProperty::Error);
    EXPECT_TRUE(output.text.startsWith("Cannot create the output window (")) << output.text.toStdString();
    EXPECT_TRUE(output.text.contains("already exists")) << "OGRE's reason is shown: " << output.text.toStdString();
    EXPECT_TRUE(output.text.endsWith("the projector shows nothing")) << output.text.toStdString();
    EXPECT_EQ(projector_->outputWindow(), nullptr) << "no half-made window is kept";
    EXPECT_EQ(visibleProjectorWindows(), 0);
    // rviz goes on: its main view renders, the projector's frame timer runs without a window.
    EXPECT_TRUE(waitForMainViewFrames(10));
    const std::uint64_t rendered = projector_->framesRendered();
    spinFor(0.3);
    EXPECT_EQ(projector_->framesRendered(), rendered) << "nothing to render into";
    EXPECT_TRUE(projector_->isEnabled());
    EXPECT_EQ(statusOf(projector_, "Output").level, rviz::StatusProperty::Error) << "the error stays";
  }
  // The names are free again: the next setting makes a window, and the projector shows the path.
  projector_->subProp("Anti-aliasing")->setValue(false);
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
  const Status output = statusOf(projector_, "Output");
  EXPECT_NE(output.level, rviz::StatusProperty::Error) << output.text.toStdString();
  EXPECT_FALSE(output.text.contains("Cannot create")) << output.text.toStdString();
  EXPECT_GT(countColour(imagePart(grabWithArrows()), kArrowMagenta), 100) << "the projector works again";
  EXPECT_EQ(visibleProjectorWindows(), 1);
}
