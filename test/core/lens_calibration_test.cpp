// sameLens (issue 23, defect 1): a CameraInfo republished with every camera frame is the same lens;
// any one changed value is a new one.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "rviz_projector/core/lens_calibration.h"

using rviz_projector::LensCalibration;
using rviz_projector::sameLens;

namespace
{
LensCalibration pa503w()
{
  LensCalibration c;
  c.width = 1280;
  c.height = 800;
  c.distortion_model = "plumb_bob";
  c.D = {0.0, 0.0, 0.0, 0.0, 0.0};
  c.K = {1900, 0, 640, 0, 1900, 817, 0, 0, 1};
  c.P = {1900, 0, 640, 0, 0, 1900, 750, 0, 0, 0, 1, 0};
  return c;
}
}  // namespace

TEST(LensCalibration, EqualValuesAreTheSameLensAndEachFieldCounts)
{
  EXPECT_TRUE(sameLens(pa503w(), pa503w()));
  const std::vector<std::function<void(LensCalibration&)>> changes = {
      [](LensCalibration& c) { c.width = 1920; },
      [](LensCalibration& c) { c.height = 1080; },
      [](LensCalibration& c) { c.distortion_model = "rational_polynomial"; },
      [](LensCalibration& c) { c.D[0] = -0.05; },
      [](LensCalibration& c) { c.D.push_back(0.0); },
      [](LensCalibration& c) { c.K[2] = 639.5; },
      [](LensCalibration& c) { c.P[6] = 817; },
      [](LensCalibration& c) { c.binning_x = 2; },
      [](LensCalibration& c) { c.binning_y = 2; },
      [](LensCalibration& c) { c.roi_x_offset = 10; },
      [](LensCalibration& c) { c.roi_y_offset = 10; },
      [](LensCalibration& c) { c.roi_width = 640; },
      [](LensCalibration& c) { c.roi_height = 400; },
  };
  for (std::size_t i = 0; i < changes.size(); ++i)
  {
    LensCalibration changed = pa503w();
    changes[i](changed);
    EXPECT_FALSE(sameLens(pa503w(), changed)) << "change " << i << " went unnoticed";
    EXPECT_FALSE(sameLens(changed, pa503w())) << "change " << i;
  }
  LensCalibration nan = pa503w();
  nan.K[0] = std::nan("");
  EXPECT_FALSE(sameLens(nan, nan)) << "NaN is never the same lens (and is refused anyway)";
}
