// The advice ProjectorCamera gives about rviz's main view: which renderers count as software,
// and when a warning is due.
#include <gtest/gtest.h>

#include <string>

#include "rviz_projector/displays/main_view_cost.h"

using rviz_projector::isSoftwareRenderer;
using rviz_projector::mainViewCostWarning;

TEST(MainViewCost, SoftwareRenderersAreRecognisedByTheirGlRendererString)
{
  EXPECT_TRUE(isSoftwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
  EXPECT_TRUE(isSoftwareRenderer("softpipe"));
  EXPECT_TRUE(isSoftwareRenderer("Software Rasterizer"));
  EXPECT_TRUE(isSoftwareRenderer("SWR (LLVM 12.0.0, 256 bits)"));
  EXPECT_FALSE(isSoftwareRenderer("Mesa Intel(R) UHD Graphics 620 (KBL GT2)"));
  EXPECT_FALSE(isSoftwareRenderer("NVIDIA GeForce RTX 3060/PCIe/SSE2"));
  EXPECT_FALSE(isSoftwareRenderer("AMD Radeon Graphics (renoir, LLVM 15.0.7, DRM 3.49, 6.1.0-13-amd64)"));
  EXPECT_FALSE(isSoftwareRenderer(""));
}

TEST(MainViewCost, WarnsOnlyForMultisamplingOnASoftwareRenderer)
{
  const std::string llvmpipe = "llvmpipe (LLVM 15.0.6, 256 bits)";
  const std::string warning = mainViewCostWarning(4, llvmpipe);
  EXPECT_NE(warning.find("4x anti-aliasing"), std::string::npos) << warning;
  EXPECT_NE(warning.find(llvmpipe), std::string::npos) << warning;
  EXPECT_NE(warning.find("--disable-anti-aliasing"), std::string::npos) << warning;
  EXPECT_EQ(mainViewCostWarning(0, llvmpipe), "");
  EXPECT_EQ(mainViewCostWarning(1, llvmpipe), "");
  EXPECT_EQ(mainViewCostWarning(4, "Mesa Intel(R) UHD Graphics 620 (KBL GT2)"), "");
}
