// The distortion warp in rendered pixels (issue 24): what the window shows through a distorting lens
// beyond where its targets land (projector_pixels_test.cpp measures that against cv::projectPoints):
// nothing of an earlier frame stays, whether the window, the ideal render's texture or only the parts
// of it the last frame lit are put back to the background; drawing only the occupied cells (software
// renderer) shows the picture of the whole mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include <OgreManualObject.h>
#include <OgreRenderSystem.h>
#include <OgreRenderTarget.h>
#include <OgreRenderWindow.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>
#include <OgreViewport.h>
#include <RenderSystems/GL/OgreGLContext.h>
#include <QColor>
#include <rviz/display.h>

#include "rviz_projector/displays/projection_change_counter.h"
#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "rviz_projector/displays/viewport_clear.h"
#include "projector_test_fixture.h"

// Last: Xlib's macros (None, Status, ...) must not meet the headers above.
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glx.h>
#undef None
#undef Status
#undef Bool
#undef Always
#undef Success

using rviz_projector_test::distortedInfo;
using rviz_projector_test::Mount;
using rviz_projector_test::PixelOracle;
using rviz_projector_test::ProjectorCameraTest;
using rviz_projector_test::projectorInfo;
using rviz_projector_test::saveShot;
using rviz_projector_test::Vec2;

namespace
{
/// The viewports OGRE draws into the warp's ideal-render texture, in z-order (none: no texture).
std::vector<const Ogre::Viewport*> idealTextureViewports()
{
  std::vector<const Ogre::Viewport*> viewports;
  auto targets = Ogre::Root::getSingleton().getRenderSystem()->getRenderTargetIterator();
  while (targets.hasMoreElements())
  {
    Ogre::RenderTarget* target = targets.getNext();
    if (target->getName().find("rviz_projector_warp_texture_") != std::string::npos)
    {
      for (unsigned short i = 0; i < target->getNumViewports(); ++i)
      {
        viewports.push_back(target->getViewport(i));  // by z-order
      }
    }
  }
  return viewports;
}
/// The projector 2 m above the floor looking straight down through the wide-angle lens (k1 = -0.2,
/// k2 = 0.05), and the oracle of where it must light floor points.
class WarpPixelsTest : public ProjectorCameraTest
{
protected:
  const Mount down_{{0.3, -0.2, 2.0}, 1.0, 0.0, 0.0, 0.0};
  const sensor_msgs::CameraInfo wide_ = distortedInfo({-0.2, 0.05, 0, 0, 0});
  const PixelOracle oracle_{wide_, down_};

  /// Mounts the projector, adds a floor disc `diameter` metres across at the floor point the image
  /// pixel `pixel` sees, publishes the lens and waits until the disc is ready and the window shown.
  void showDisc(const Vec2& pixel, double diameter)
  {
    mount(down_);
    addTarget(oracle_.floorPoint(pixel), diameter);
    info_pub_.publish(wide_);
    ASSERT_TRUE(waitFor([&] { return projector_->hasLens() && targetsReady(); }));
    ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
  }
  /// The diameter, metres, of a floor disc at image pixel `pixel` that is `pixels` across there.
  double discDiameter(const Vec2& pixel, double pixels) const
  {
    return pixels * oracle_.depth(oracle_.floorPoint(pixel)) / oracle_.fx();
  }
};
}  // namespace

// Issue 24: under the warp's mesh the window is not cleared first (the mesh covers every pixel of
// the image and draws the ideal render, cleared to the background): nothing of an earlier frame
// may stay, not even in the image's edge rows and columns. A floor disc far larger than the view
// lights every pixel; moved out of view, every image pixel must be the black background again.
// Then lit again, and the projector's pose lost (its frame unknown): the mesh is not drawn and the
// window must be blanked all the same.
TEST_F(WarpPixelsTest, ThroughALensNothingOfAnEarlierFrameStays)
{
  const PixelOracle& oracle = oracle_;
  const Vec2 centre = oracle.floorPoint({640, 400});
  ASSERT_NO_FATAL_FAILURE(showDisc({640, 400}, 200.0));
  auto isGreen = [](QRgb c) { return qGreen(c) > 128 && qRed(c) < 100 && qBlue(c) < 100; };
  auto isBlack = [](QRgb c) { return qRed(c) < 30 && qGreen(c) < 30 && qBlue(c) < 30; };
  auto count = [](const QImage& image, const std::function<bool(QRgb)>& pred) {
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
    {
      for (int x = 0; x < image.width(); ++x)
      {
        n += pred(image.pixel(x, y)) ? 1 : 0;
      }
    }
    return n;
  };
  // The image part of the window once every pixel is `pred` (or the last grab after the timeout).
  auto imageWhenAll = [&](const std::function<bool(QRgb)>& pred) {
    return imagePart(grabWhen([&](const QImage& f) {
                       const QImage image = imagePart(f, oracle);
                       return !image.isNull() && count(image, pred) == image.width() * image.height();
                     }),
                     oracle);
  };
  auto moveDisc = [&](double x) { moveTarget(0, {x, centre.y}); };

  const QImage lit = imageWhenAll(isGreen);
  ASSERT_FALSE(lit.isNull());
  ASSERT_EQ(count(lit, isGreen), lit.width() * lit.height()) << "the disc lights every image pixel";

  moveDisc(centre.x + 1000.0);
  const QImage dark = imageWhenAll(isBlack);
  ASSERT_FALSE(dark.isNull());
  EXPECT_EQ(count(dark, isBlack), dark.width() * dark.height())
      << "pixels left from the earlier frame: " << dark.width() * dark.height() - count(dark, isBlack)
      << " (first row " << count(dark.copy(0, 0, dark.width(), 1), isBlack) << " of " << dark.width() << " black)";

  moveDisc(centre.x);
  const QImage lit_again = imageWhenAll(isGreen);
  ASSERT_EQ(count(lit_again, isGreen), lit_again.width() * lit_again.height()) << "lit again";
  projector_->subProp("Frame")->setValue("rviz_projector_test_unknown_frame");
  const QImage no_pose = imageWhenAll(isBlack);
  ASSERT_FALSE(no_pose.isNull());
  EXPECT_EQ(count(no_pose, isBlack), no_pose.width() * no_pose.height())
      << "without a pose the window is blanked: " << no_pose.width() * no_pose.height() - count(no_pose, isBlack)
      << " pixels left from the earlier frame";
}

// Issue 24, the warp's cost on a software renderer: only the cells with something on them are
// drawn (into a window cleared to the background). The picture must be the one the whole mesh
// draws, pixel for pixel: twenty targets spread over the image, through the wide-angle lens, drawn
// once with every cell (RVIZ_PROJECTOR_WARP_CELLS=all: the path whose accuracy the tests above
// measure against cv::projectPoints) and once with the occupied cells only.
TEST_F(WarpPixelsTest, ThroughALensOnlyOccupiedCellsAreDrawnAndThePictureIsTheWholeMeshs)
{
  const sensor_msgs::CameraInfo& info = wide_;
  const PixelOracle& oracle = oracle_;
  mount(down_);
  for (int j = 0; j < 4; ++j)
  {
    for (int i = 0; i < 5; ++i)
    {
      const Vec2 floor = oracle.floorPoint({77.0 + 283.0 * i, 56.0 + 229.0 * j});
      addTarget(floor, 30.0 * oracle.depth(floor) / oracle.fx());
    }
  }
  // Without D: the window's viewport as the output made it clears depth and stencil together (a
  // depth clear alone is a per-pixel masked write on the software renderer, doc/dev/performance.md).
  const unsigned all_three = Ogre::FBT_COLOUR | Ogre::FBT_DEPTH | Ogre::FBT_STENCIL;
  ASSERT_TRUE(waitFor([&] { return projector_->outputWindow() && projector_->outputWindow()->isVisible(); }));
  EXPECT_TRUE(projector_->outputWindow()->renderWindow()->getViewport(0)->getClearEveryFrame());
  EXPECT_EQ(projector_->outputWindow()->renderWindow()->getViewport(0)->getClearBuffers(), all_three);
  auto isGreen = [](QRgb c) { return qGreen(c) > 128 && qRed(c) < 100 && qBlue(c) < 100; };
  auto greenCount = [&](const QImage& image) {
    int n = 0;
    for (int y = 0; y < image.height(); ++y)
    {
      for (int x = 0; x < image.width(); ++x)
      {
        n += isGreen(image.pixel(x, y)) ? 1 : 0;
      }
    }
    return n;
  };
  // Shown through the lens with `cells` ("all" or "occupied") and the read-back `readback` ("direct"
  // or "whole", texture_rows.h); the image part once every target is.
  auto showWith = [&](const char* cells, const char* readback) {
    setenv("RVIZ_PROJECTOR_WARP_CELLS", cells, 1);
    setenv("RVIZ_PROJECTOR_WARP_READBACK", readback, 1);
    info_pub_.publish(projectorInfo(1280, 800, 1900, 639.5, 399.5));  // no D: the warp is released
    EXPECT_TRUE(waitFor([&] { return projector_->hasLens() && !statusOf(projector_, "Distortion").present; }));
    info_pub_.publish(info);  // the lens again: the warp made anew with `cells`
    const bool occupied = std::string(cells) == "occupied";
    // On this machine's llvmpipe (OpenGL 4.5) "direct" must really read directly.
    const QString read = std::string(readback) == "direct" ? "(read back directly)" : "(read back whole)";
    EXPECT_TRUE(waitFor([&] {
      const auto s = statusOf(projector_, "Distortion");
      return s.present && s.text.contains("warp") && s.text.contains("only its cells") == occupied &&
             (!occupied || s.text.contains(read));
    })) << statusOf(projector_, "Distortion").text.toStdString();
    EXPECT_TRUE(waitFor([&] { return targetsReady() && projector_->outputWindow() &&
                                     projector_->outputWindow()->isVisible(); }));
    return imagePart(grabWhen([&](const QImage& f) { return greenCount(imagePart(f, oracle)) > 20 * 400; }), oracle);
  };
  auto windowView = [&] { return projector_->outputWindow()->renderWindow()->getViewport(0); };
  const QImage whole = showWith("all", "direct");
  EXPECT_FALSE(windowView()->getClearEveryFrame()) << "the whole mesh covers the window: nothing to clear";
  // Cells the warp's mesh draws now, from OGRE's own objects (its triangles / 2; -1: no mesh).
  auto cellsDrawn = [&]() -> long {
    for (const auto& manager : Ogre::Root::getSingleton().getSceneManagers())
    {
      for (const auto& object : manager.second->getMovableObjects("ManualObject"))
      {
        if (object.first.rfind("rviz_projector_warp_mesh_", 0) != 0)
        {
          continue;
        }
        const auto* mesh = static_cast<const Ogre::ManualObject*>(object.second);
        long indices = 0;
        for (Ogre::ManualObject::ManualObjectSection* section : mesh->getSections())
        {
          indices += long(section->getRenderOperation()->indexData->indexCount);
        }
        return mesh->isVisible() ? indices / 6 : 0;
      }
    }
    return -1;
  };
  EXPECT_EQ(cellsDrawn(), 32 * 20) << "every cell of the 32x20 warp";
  const QImage read_whole = showWith("occupied", "whole");
  // 20 small targets: each on at most 3 x 3 cells (core WarpCellScan); none drawn means none read.
  const long most_cells = 20 * 9;
  EXPECT_GE(cellsDrawn(), 20);
  EXPECT_LE(cellsDrawn(), most_cells) << "read back whole: more cells than the targets are on";
  const QImage occupied = showWith("occupied", "direct");
  EXPECT_GE(cellsDrawn(), 20);
  EXPECT_LE(cellsDrawn(), most_cells) << "read back directly: more cells than the targets are on";
  unsetenv("RVIZ_PROJECTOR_WARP_CELLS");
  unsetenv("RVIZ_PROJECTOR_WARP_READBACK");
  ASSERT_FALSE(whole.isNull());
  ASSERT_GT(greenCount(whole), 20 * 400) << "the targets are shown";
  for (const QImage* cells : {&read_whole, &occupied})
  {
    ASSERT_EQ(whole.size(), cells->size());
    int differ = 0;
    int most = 0;  // largest difference of a colour channel
    for (int y = 0; y < whole.height(); ++y)
    {
      for (int x = 0; x < whole.width(); ++x)
      {
        const QRgb a = whole.pixel(x, y), b = cells->pixel(x, y);
        const int d = std::max({std::abs(qRed(a) - qRed(b)), std::abs(qGreen(a) - qGreen(b)),
                                std::abs(qBlue(a) - qBlue(b))});
        differ += d > 0 ? 1 : 0;
        most = std::max(most, d);
      }
    }
    EXPECT_EQ(differ, 0) << "pixels that differ between the whole mesh and its occupied cells read back "
                         << (cells == &occupied ? "directly" : "whole") << ", by up to " << most;
  }
  saveShot(occupied, "warp_occupied_cells");
  // Through the lens, both passes too: the window's viewport, cleared again now that only cells are
  // drawn (its colour alone: the warp's mesh tests no depth), and the ideal view's texture: the
  // eraser's viewport first (it paints the blocks the last frame lit back to the background, and
  // clears nothing), then the scene's, which clears depth and stencil only (20 small targets light
  // far less than an eighth of the picture). From OGRE's own objects.
  Ogre::Viewport* window_view = windowView();
  EXPECT_TRUE(window_view->getClearEveryFrame());
  EXPECT_EQ(window_view->getClearBuffers(), static_cast<unsigned>(Ogre::FBT_COLOUR));
  // A frame more (the last one may have been the first after the lens: that one clears all).
  rviz_projector::ProjectionChangeCounter::bump();
  projector_->renderNow();
  const std::vector<const Ogre::Viewport*> texture_views = idealTextureViewports();
  ASSERT_EQ(texture_views.size(), 2u) << "the warp's texture: the eraser's viewport and the scene's";
  EXPECT_LT(texture_views[0]->getZOrder(), texture_views[1]->getZOrder()) << "the eraser paints before the scene";
  EXPECT_EQ(rviz_projector::clearedBuffers(*texture_views[0]), 0u);
  EXPECT_EQ(rviz_projector::clearedBuffers(*texture_views[1]),
            static_cast<unsigned>(Ogre::FBT_DEPTH | Ogre::FBT_STENCIL));
  // The lens without D again: the scene is drawn into the window itself, which clears its depth and
  // stencil again (the targets' depth order needs them).
  info_pub_.publish(projectorInfo(1280, 800, 1900, 639.5, 399.5));
  EXPECT_TRUE(waitFor([&] { return projector_->hasLens() && !statusOf(projector_, "Distortion").present; }));
  EXPECT_TRUE(waitFor([&] {
    window_view = windowView();
    return window_view->getClearEveryFrame() && window_view->getClearBuffers() == all_three;
  })) << "clears " << window_view->getClearBuffers();
}

// Issue 24 on a software renderer: the ideal render's texture is not cleared whole each frame; the
// eraser paints the blocks the last frame lit back to the background (warp_eraser.h). A disc ~80 px
// across jumps around the wide-angle lens's image (onto a spot overlapping the last one, into the
// corners), on a black and then a blue background: every frame must show the disc where
// cv::projectPoints puts it (PixelOracle) and nothing else, every other pixel exactly the background
// (one level of rounding allowed).
TEST_F(WarpPixelsTest, ThroughALensASpotThatJumpsAroundLeavesNothingBehindOnAnyBackground)
{
  const PixelOracle& oracle = oracle_;
  constexpr double kDiscPixels = 80.0;
  ASSERT_NO_FATAL_FAILURE(showDisc({640, 400}, discDiameter({640, 400}, kDiscPixels)));
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Distortion").text.contains("only its cells"); }))
      << "this test is about the occupied cells (software renderer): "
      << statusOf(projector_, "Distortion").text.toStdString();
  struct Count
  {
    int stray = 0;  // not the background, away from the disc
    int lit = 0;    // not the background, on the disc
  };
  // Pixels that are not `background` (one level allowed), away from the disc at `centre` (beyond
  // its radius plus 6 px: the lens squeezes the disc, never stretches it by that much) and on it
  // (within half its radius).
  auto countPixels = [&](const QImage& image, const Vec2& centre, const QColor& background) {
    Count c;
    for (int y = 0; y < image.height(); ++y)
    {
      for (int x = 0; x < image.width(); ++x)
      {
        const QRgb p = image.pixel(x, y);
        const bool other = std::abs(qRed(p) - background.red()) > 1 || std::abs(qGreen(p) - background.green()) > 1 ||
                           std::abs(qBlue(p) - background.blue()) > 1;
        const double r = std::hypot(x - centre.x, y - centre.y);
        c.stray += other && r > kDiscPixels / 2 + 6 ? 1 : 0;
        c.lit += other && r < kDiscPixels / 4 ? 1 : 0;
      }
    }
    return c;
  };
  const std::vector<Vec2> spots{{640, 400}, {668, 421}, {200, 150}, {1190, 60}, {1200, 760}, {60, 740}, {640, 400}};
  const int inner = int(3.14159 * kDiscPixels * kDiscPixels / 16 * 0.8);  // most of the inner half
  for (const QColor& background : {QColor(0, 0, 0), QColor(20, 60, 130)})
  {
    projector_->subProp("Background color")->setValue(background);
    for (std::size_t k = 0; k < spots.size(); ++k)
    {
      const Vec2 floor = oracle.floorPoint(spots[k]);
      moveTarget(0, floor);
      const Vec2 centre = oracle.imagePixel(floor);
      const QImage image = imagePart(grabWhen([&](const QImage& f) {
                                       const Count c = countPixels(imagePart(f, oracle), centre, background);
                                       return c.stray == 0 && c.lit >= inner;
                                     }),
                                     oracle);
      ASSERT_FALSE(image.isNull());
      const Count c = countPixels(image, centre, background);
      EXPECT_EQ(c.stray, 0) << "spot " << k << " (" << spots[k].x << ", " << spots[k].y << ") on background "
                            << background.name().toStdString() << ": pixels left from earlier frames";
      EXPECT_GE(c.lit, inner) << "spot " << k << ": the disc is not where cv::projectPoints puts it";
      // That frame was drawn with the eraser (the frame before it was read back and lit little): the
      // scene's viewport cleared depth and stencil only.
      const std::vector<const Ogre::Viewport*> views = idealTextureViewports();
      ASSERT_EQ(views.size(), 2u);
      EXPECT_EQ(rviz_projector::clearedBuffers(*views[1]), static_cast<unsigned>(Ogre::FBT_DEPTH | Ogre::FBT_STENCIL))
          << "spot " << k << ": the texture was cleared whole, the eraser not used";
      if (k == 1)
      {
        saveShot(image, background == QColor(0, 0, 0) ? "warp_erased_black" : "warp_erased_blue");
      }
    }
  }
}

// A direct read of the ideal render that fails at run time (here a pixel-pack buffer left bound in the
// GL context the texture is drawn with, as another plugin could leave it: texture_rows.h refuses to
// read into it) draws every cell that frame and reads through OGRE from then on. The "Distortion"
// status must say so at once (a warning, "read back whole", the reason), not keep claiming the direct
// read until the lens changes; and the pictures after it must still be right, while the buffer stays
// bound (OGRE's read would go into it too: every cell is drawn) and once it is gone.
TEST_F(WarpPixelsTest, ThroughALensAFailedDirectReadFallsBackAndTheStatusSaysSo)
{
  const PixelOracle& oracle = oracle_;
  unsetenv("RVIZ_PROJECTOR_WARP_READBACK");
  ASSERT_NO_FATAL_FAILURE(showDisc({640, 400}, discDiameter({640, 400}, 80.0)));
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Distortion").text.contains("(read back directly)"); }))
      << statusOf(projector_, "Distortion").text.toStdString();
  EXPECT_EQ(statusOf(projector_, "Distortion").level, rviz::StatusProperty::Ok);

  // The GL context OGRE draws the warp's texture with (its render target says which).
  Ogre::GLContext* context = nullptr;
  auto targets = Ogre::Root::getSingleton().getRenderSystem()->getRenderTargetIterator();
  while (targets.hasMoreElements())
  {
    Ogre::RenderTarget* target = targets.getNext();
    if (target->getName().find("rviz_projector_warp_texture_") != std::string::npos)
    {
      target->getCustomAttribute("GLCONTEXT", &context);
    }
  }
  ASSERT_NE(context, nullptr) << "no GL context for the warp's texture";
  const auto gen_buffers = reinterpret_cast<PFNGLGENBUFFERSPROC>(
      glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glGenBuffers")));
  const auto bind_buffer = reinterpret_cast<PFNGLBINDBUFFERPROC>(
      glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glBindBuffer")));
  const auto delete_buffers = reinterpret_cast<PFNGLDELETEBUFFERSPROC>(
      glXGetProcAddressARB(reinterpret_cast<const GLubyte*>("glDeleteBuffers")));
  ASSERT_TRUE(gen_buffers && bind_buffer && delete_buffers);
  // Runs `f` with OGRE's texture context current, then makes current again what was.
  auto inTextureContext = [&](const std::function<void()>& f) {
    Display* display = glXGetCurrentDisplay();
    const GLXDrawable draw = glXGetCurrentDrawable();
    const GLXDrawable read = glXGetCurrentReadDrawable();
    const GLXContext current = glXGetCurrentContext();
    context->setCurrent();
    f();
    if (display && current)
    {
      glXMakeContextCurrent(display, draw, read, current);
    }
  };
  GLuint buffer = 0;
  inTextureContext([&] {
    gen_buffers(1, &buffer);
    bind_buffer(GL_PIXEL_PACK_BUFFER, buffer);
  });
  ASSERT_NE(buffer, 0u);
  // A frame with the buffer bound: the direct read refuses it, and the status says so at once.
  rviz_projector::ProjectionChangeCounter::bump();
  projector_->renderNow();
  const auto status = statusOf(projector_, "Distortion");
  EXPECT_TRUE(status.text.contains("(read back whole)")) << status.text.toStdString();
  EXPECT_TRUE(status.text.contains("direct read of the ideal render failed (a pixel-pack buffer was bound)"))
      << status.text.toStdString();
  EXPECT_EQ(status.level, rviz::StatusProperty::Warn) << status.text.toStdString();

  // Still bound, then unbound: every picture must be right, the disc where the oracle puts it and
  // nothing else lit (while bound OGRE's read cannot work either: every cell is drawn).
  auto isLit = [](QRgb c) { return qRed(c) > 30 || qGreen(c) > 30 || qBlue(c) > 30; };
  int shown = 0;
  for (const Vec2& spot : {Vec2{700, 430}, Vec2{200, 150}, Vec2{1150, 700}, Vec2{640, 400}})
  {
    if (shown++ == 2)
    {
      inTextureContext([&] {
        bind_buffer(GL_PIXEL_PACK_BUFFER, 0);
        delete_buffers(1, &buffer);
      });
    }
    const Vec2 floor = oracle.floorPoint(spot);
    moveTarget(0, floor);
    const Vec2 centre = oracle.imagePixel(floor);
    auto stray = [&](const QImage& image, int* on_disc) {
      int n = 0, on = 0;
      for (int y = 0; y < image.height(); ++y)
      {
        for (int x = 0; x < image.width(); ++x)
        {
          const double r = std::hypot(x - centre.x, y - centre.y);
          const bool lit = isLit(image.pixel(x, y));
          n += lit && r > 46.0 ? 1 : 0;
          on += lit && r < 20.0 ? 1 : 0;
        }
      }
      *on_disc = on;
      return n;
    };
    int on_disc = 0;
    const QImage image = imagePart(grabWhen([&](const QImage& f) {
                                     int on = 0;
                                     return stray(imagePart(f, oracle), &on) == 0 && on > 1000;
                                   }),
                                   oracle);
    EXPECT_EQ(stray(image, &on_disc), 0) << "spot (" << spot.x << ", " << spot.y << "), pack buffer "
                                         << (shown <= 2 ? "bound" : "unbound") << ": pixels lit away from the disc";
    EXPECT_GT(on_disc, 1000) << "spot (" << spot.x << ", " << spot.y << "), pack buffer "
                             << (shown <= 2 ? "bound" : "unbound") << ": the disc is missing";
  }
  EXPECT_TRUE(statusOf(projector_, "Distortion").text.contains("(read back whole)"));
}
