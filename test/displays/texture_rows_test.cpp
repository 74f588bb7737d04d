// How the distortion warp reads its ideal render back (texture_rows.h): directly through OpenGL 4.5
// where OGRE's OpenGL render system offers it for an RGBA texture, else whole through OGRE; the
// RVIZ_PROJECTOR_WARP_READBACK setting. (The reads themselves: projector_pixels.test, through a lens.)
#include <gtest/gtest.h>

#include <string>

#include "rviz_projector/displays/texture_rows.h"

using rviz_projector::chooseRowReadback;
using rviz_projector::RowReadback;

namespace
{
const std::string kGl = "OpenGL Rendering Subsystem";  // Ogre::RenderSystem::getName() of RenderSystem_GL
}

TEST(ChooseRowReadback, DirectOnOpenGl45AndLaterForAnRgbaTextureOnly)
{
  std::string note;
  EXPECT_EQ(chooseRowReadback("", kGl, 4, 5, true, &note), RowReadback::Direct);
  EXPECT_EQ(chooseRowReadback("", kGl, 4, 6, true, &note), RowReadback::Direct);
  EXPECT_EQ(chooseRowReadback("", kGl, 5, 0, true, &note), RowReadback::Direct);
  EXPECT_EQ(chooseRowReadback("auto", kGl, 4, 5, true, &note), RowReadback::Direct);
  EXPECT_TRUE(note.empty()) << note;
  EXPECT_EQ(chooseRowReadback("", kGl, 4, 4, true, &note), RowReadback::Whole);  // no glGetTextureSubImage
  EXPECT_EQ(chooseRowReadback("", kGl, 3, 9, true, &note), RowReadback::Whole);
  EXPECT_EQ(chooseRowReadback("", kGl, 4, 5, false, &note), RowReadback::Whole);  // another byte order
  EXPECT_EQ(chooseRowReadback("", "Direct3D11 Rendering Subsystem", 4, 5, true, &note), RowReadback::Whole);
  EXPECT_EQ(chooseRowReadback("", "", 0, 0, true, &note), RowReadback::Whole);  // no render system
  EXPECT_TRUE(note.empty()) << "auto says nothing: " << note;
}

TEST(ChooseRowReadback, TheSettingWinsWhereItCanAndSaysWhyWhereItCannot)
{
  std::string note;
  EXPECT_EQ(chooseRowReadback("whole", kGl, 4, 5, true, &note), RowReadback::Whole);
  EXPECT_EQ(chooseRowReadback("WHOLE", kGl, 4, 5, true, &note), RowReadback::Whole);
  EXPECT_EQ(chooseRowReadback("direct", kGl, 4, 5, true, &note), RowReadback::Direct);
  EXPECT_TRUE(note.empty()) << note;
  EXPECT_EQ(chooseRowReadback("direct", kGl, 3, 3, true, &note), RowReadback::Whole);
  EXPECT_NE(note.find("OpenGL 4.5"), std::string::npos) << note;
  EXPECT_NE(note.find("3.3"), std::string::npos) << note;
  note.clear();
  EXPECT_EQ(chooseRowReadback("sideways", kGl, 4, 5, true, &note), RowReadback::Direct);  // auto
  EXPECT_NE(note.find("sideways"), std::string::npos) << note;
  EXPECT_NE(note.find("direct, whole, auto"), std::string::npos) << note;
}
