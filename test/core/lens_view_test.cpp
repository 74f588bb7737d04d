// lens_view: the lens of a scaled image (hand-computed pixel mapping) and the narrow-view warning.
#include <gtest/gtest.h>

#include "rviz_projector/core/lens_view.h"

using rviz_projector::narrowViewWarning;
using rviz_projector::PinholeModel;
using rviz_projector::scaledLens;
using rviz_projector::Vec2;
using rviz_projector::Vec3;

TEST(LensView, ScaledLensMapsPixelCentresAsTheResampledImageDoes)
{
  const PinholeModel lens(1280, 800, 1000.0, 1010.0, 639.5, 420.25, 12.0, -3.0);
  const PinholeModel half = scaledLens(lens, 640, 400);
  EXPECT_EQ(half.width(), 640u);
  EXPECT_EQ(half.height(), 400u);
  // Hand computation: s = 0.5; fx' = 500, cx' = (639.5 + 0.5) * 0.5 - 0.5 = 319.5; Tx' = 6.
  EXPECT_DOUBLE_EQ(half.fx(), 500.0);
  EXPECT_DOUBLE_EQ(half.fy(), 505.0);
  EXPECT_DOUBLE_EQ(half.cx(), 319.5);
  EXPECT_DOUBLE_EQ(half.cy(), 209.875);
  EXPECT_DOUBLE_EQ(half.tx(), 6.0);
  EXPECT_DOUBLE_EQ(half.ty(), -1.5);
  // A point seen at pixel u in the full image lies at (u + 0.5) * s - 0.5 in the scaled one: the
  // pixel's area maps onto the scaled pixel's area. Raw formula u = (fx x + cx z + Tx) / z.
  const Vec3 p{0.3, -0.2, 2.0};
  const double u = (1000.0 * p.x + 639.5 * p.z + 12.0) / p.z;
  const double v = (1010.0 * p.y + 420.25 * p.z - 3.0) / p.z;
  Vec2 scaled;
  ASSERT_TRUE(half.project(p, scaled));
  EXPECT_NEAR(scaled.x, (u + 0.5) * 0.5 - 0.5, 1e-9);
  EXPECT_NEAR(scaled.y, (v + 0.5) * 0.5 - 0.5, 1e-9);
}

TEST(LensView, UnevenScaleKeepsEachAxis)
{
  // 1024x768 shown as 640x480 (s = 0.625 on both) and a rounded 853x480 (sx != sy).
  const PinholeModel lens(1024, 768, 900.0, 900.0, 511.5, 383.5);
  const PinholeModel shown = scaledLens(lens, 853, 480);
  EXPECT_NEAR(shown.fx(), 900.0 * 853.0 / 1024.0, 1e-12);
  EXPECT_NEAR(shown.fy(), 900.0 * 480.0 / 768.0, 1e-12);
  EXPECT_NEAR(shown.cx(), 512.0 * 853.0 / 1024.0 - 0.5, 1e-12);
  EXPECT_NEAR(shown.cy(), 384.0 * 480.0 / 768.0 - 0.5, 1e-12);
}

TEST(LensView, NarrowViewIsReported)
{
  EXPECT_EQ(narrowViewWarning(PinholeModel(1280, 800, 1900.0, 1900.0, 640.0, 750.0)), "");
  // fx = 1e9: 1280 px span 1.3e-6 rad (7e-5 degrees): practically nothing is seen.
  const std::string w = narrowViewWarning(PinholeModel(1280, 800, 1e9, 1e9, 640.0, 400.0));
  EXPECT_NE(w.find("Field of view"), std::string::npos) << w;
  EXPECT_NE(w.find("1e+09"), std::string::npos) << w;
  // Only one axis narrow is enough.
  EXPECT_NE(narrowViewWarning(PinholeModel(1280, 800, 1000.0, 1e7, 640.0, 400.0)), "");
  // The bound is 1e-3 rad: 1280 px need fx < 1.28e6, 800 px fy < 8e5. Just inside is fine, just
  // outside is not.
  EXPECT_EQ(narrowViewWarning(PinholeModel(1280, 800, 1.27e6, 7.9e5, 640.0, 400.0)), "");
  EXPECT_NE(narrowViewWarning(PinholeModel(1280, 800, 1.27e6, 8.1e5, 640.0, 400.0)), "");
}
