// Gray code frames and decoding: the bit order against OpenCV's own decoder (getProjPixel), exact
// decoding of the patterns themselves, a simulated camera, and captures that do not fit.
#include "rviz_projector/core/gray_code.h"

#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/structured_light.hpp>

#include "structured_light_sim.h"

namespace rviz_projector
{
namespace
{
std::vector<cv::Mat> frameImages(const std::vector<PatternFrame>& frames)
{
  std::vector<cv::Mat> images;
  for (const PatternFrame& frame : frames)
  {
    images.push_back(frame.image);
  }
  return images;
}

TEST(GrayCodeFrames, WhiteBlackThenOpenCvPatternsNamed)
{
  const std::vector<PatternFrame> frames = grayCodeFrames(1280, 800);
  ASSERT_EQ(frames.size(), 44u);  // 2 + 2 * (11 + 10)
  EXPECT_EQ(frames[0].name, "white");
  EXPECT_EQ(frames[1].name, "black");
  EXPECT_EQ(frames[2].name, "column bit 10 of 11 (MSB)");
  EXPECT_EQ(frames[3].name, "column bit 10 of 11 (MSB) inverse");
  EXPECT_EQ(frames[23].name, "column bit 0 of 11 (LSB) inverse");
  EXPECT_EQ(frames[24].name, "row bit 9 of 10 (MSB)");
  EXPECT_EQ(frames[43].name, "row bit 0 of 10 (LSB) inverse");
  EXPECT_EQ(cv::countNonZero(frames[0].image != 255), 0);
  EXPECT_EQ(cv::countNonZero(frames[1].image), 0);
  std::vector<cv::Mat> expected;
  cv::structured_light::GrayCodePattern::create(1280, 800)->generate(expected);
  ASSERT_EQ(expected.size(), 42u);
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    ASSERT_EQ(frames[i].image.type(), CV_8UC1) << frames[i].name;
    ASSERT_EQ(frames[i].image.size(), cv::Size(1280, 800)) << frames[i].name;
    if (i >= 2)
    {
      EXPECT_EQ(cv::countNonZero(frames[i].image != expected[i - 2]), 0) << frames[i].name;
    }
  }
  // Hand check: the MSB column pattern is white from column 1024 (Gray MSB = binary MSB), the row
  // LSB (Gray bit 0 = b0 xor b1) is white on rows 1, 2, 5, 6, ...
  EXPECT_EQ(frames[2].image.at<uchar>(0, 1023), 0);
  EXPECT_EQ(frames[2].image.at<uchar>(0, 1024), 255);
  for (int row : {0, 1, 2, 3, 4, 5})
  {
    EXPECT_EQ(frames[42].image.at<uchar>(row, 0), (row % 4 == 1 || row % 4 == 2) ? 255 : 0) << row;
  }
  EXPECT_TRUE(grayCodeFrames(1, 800).empty());
  EXPECT_TRUE(grayCodeFrames(1280, 0).empty());
  EXPECT_TRUE(grayCodeFrames(20000, 800).empty());
}

TEST(GrayCodeDecode, ThePatternsThemselvesDecodeToEveryPixelExactly)
{
  // Camera = projector (identity), sharp, noise free: captures are the frames.
  for (const cv::Size size : {cv::Size(1280, 800), cv::Size(100, 37)})
  {
    const std::vector<PatternFrame> frames = grayCodeFrames(size.width, size.height);
    const std::vector<cv::Mat> captures = frameImages(frames);
    const GrayDecodeResult result = decodeGrayCode(size.width, size.height, captures);
    ASSERT_TRUE(result.error.empty()) << result.error;
    const int pixels = size.area();
    EXPECT_EQ(result.lit, pixels);
    EXPECT_EQ(result.saturated, pixels);  // white is 255
    EXPECT_EQ(result.decoded, pixels);
    EXPECT_EQ(result.full, pixels);
    cv::Ptr<cv::structured_light::GrayCodePattern> opencv =
        cv::structured_light::GrayCodePattern::create(size.width, size.height);
    const std::vector<cv::Mat> patterns(captures.begin() + 2, captures.end());
    int wrong = 0, opencv_disagrees = 0;
    for (int y = 0; y < size.height; ++y)
    {
      for (int x = 0; x < size.width; ++x)
      {
        const cv::Vec2f p = result.projector.at<cv::Vec2f>(y, x);
        wrong += (p[0] != float(x) || p[1] != float(y)) ? 1 : 0;
        if (x % 7 == 0 && y % 5 == 0)
        {
          cv::Point oracle;
          const bool failed = opencv->getProjPixel(patterns, x, y, oracle);  // true = error
          opencv_disagrees += (failed || oracle.x != x || oracle.y != y) ? 1 : 0;
        }
      }
    }
    EXPECT_EQ(wrong, 0) << size;
    EXPECT_EQ(opencv_disagrees, 0) << size;
  }
}

TEST(GrayCodeDecode, CoarseBitsGiveTheBlockCentre)
{
  // A "camera" that sees every projector column but loses the 3 finest column bits and the 2 finest
  // row bits (pattern = inverse there): the block of 8 columns / 4 rows, centre by hand.
  const int w = 64, h = 32;
  std::vector<cv::Mat> captures = frameImages(grayCodeFrames(w, h));
  ASSERT_EQ(captures.size(), 2u + 2u * (6u + 5u));
  for (int k : {3, 4, 5})  // column bits 2, 1, 0: frames 2 + 2k, 2 + 2k + 1
  {
    captures[std::size_t(2 + 2 * k)] = cv::Mat(h, w, CV_8UC1, cv::Scalar(128));
    captures[std::size_t(3 + 2 * k)] = cv::Mat(h, w, CV_8UC1, cv::Scalar(128));
  }
  for (int k : {3, 4})  // row bits 1, 0
  {
    captures[std::size_t(14 + 2 * k)] = cv::Mat(h, w, CV_8UC1, cv::Scalar(128));
    captures[std::size_t(15 + 2 * k)] = cv::Mat(h, w, CV_8UC1, cv::Scalar(128));
  }
  const GrayDecodeResult result = decodeGrayCode(w, h, captures);
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_EQ(result.decoded, w * h);
  EXPECT_EQ(result.full, 0);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const cv::Vec2f p = result.projector.at<cv::Vec2f>(y, x);
      ASSERT_EQ(p[0], float(x / 8 * 8) + 3.5f) << x << ", " << y;
      ASSERT_EQ(p[1], float(y / 4 * 4) + 1.5f) << x << ", " << y;
      ASSERT_EQ(result.bits.at<cv::Vec2b>(y, x), cv::Vec2b(3, 3));
    }
  }
}

TEST(GrayCodeDecode, BlocksPastTheImageAreClippedOrRefused)
{
  // 1280 columns, 11 bits: only the MSB known. MSB 1 -> columns 1024..2047, clipped to 1024..1279.
  const int w = 1280, h = 2;
  std::vector<cv::Mat> captures = frameImages(grayCodeFrames(w, h));
  for (std::size_t k = 4; k < 24; ++k)
  {
    captures[k] = cv::Mat(h, w, CV_8UC1, cv::Scalar(128));  // column bits 9..0 lost
  }
  GrayDecodeResult result = decodeGrayCode(w, h, captures);
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_EQ(result.projector.at<cv::Vec2f>(0, 5)[0], 511.5f);
  EXPECT_EQ(result.projector.at<cv::Vec2f>(0, 1100)[0], 0.5f * (1024 + 1279));
  // Codes the projector never shows are not decoded: a 100-pixel-wide camera that sees columns
  // 1250..1349 of a 2048-column projector's column patterns (same 11 bits) through a 1280 decoder.
  const std::vector<PatternFrame> narrow = grayCodeFrames(w, h);
  const std::vector<PatternFrame> wide = grayCodeFrames(2048, h);
  captures.clear();
  for (std::size_t k = 0; k < narrow.size(); ++k)
  {
    const bool column_frame = k >= 2 && k < 24;
    const cv::Mat& source = column_frame ? wide[k].image : narrow[k].image;
    captures.push_back(source.colRange(column_frame ? 1250 : 0, column_frame ? 1350 : 100).clone());
  }
  result = decodeGrayCode(w, h, captures);
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_EQ(result.decoded, 30 * h);  // columns 1250..1279
  EXPECT_EQ(result.full, 30 * h);
  EXPECT_EQ(result.projector.at<cv::Vec2f>(1, 29)[0], 1279.0f);
  EXPECT_TRUE(std::isnan(result.projector.at<cv::Vec2f>(1, 30)[0]));
  EXPECT_TRUE(std::isnan(result.projector.at<cv::Vec2f>(1, 30)[1]));
  EXPECT_EQ(result.bits.at<cv::Vec2b>(1, 30), cv::Vec2b(0, 0));
}

TEST(GrayCodeDecode, SimulatedCameraAgreesWithOpenCvWhereFullyDecoded)
{
  // A camera finer than the projector (looking at a small part of the patch): many full decodes.
  sim::Scene scene = sim::demoScene(false);
  scene.camera.fx = scene.camera.fy = 4000.0;
  scene.supersample = 2;
  const sim::Camera camera(scene);
  const std::vector<PatternFrame> frames = grayCodeFrames(1280, 800);
  std::vector<cv::Mat> captures;
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    captures.push_back(camera.capture(frames[i].image, 100 + i));
  }
  const GrayDecodeResult result = decodeGrayCode(1280, 800, captures);
  ASSERT_TRUE(result.error.empty()) << result.error;
  EXPECT_GT(result.full, 10000);
  cv::Ptr<cv::structured_light::GrayCodePattern> opencv = cv::structured_light::GrayCodePattern::create(1280, 800);
  const std::vector<cv::Mat> patterns(captures.begin() + 2, captures.end());
  int compared = 0, disagree = 0;
  for (int y = 0; y < result.bits.rows; y += 3)
  {
    for (int x = 0; x < result.bits.cols; x += 3)
    {
      if (result.bits.at<cv::Vec2b>(y, x) != cv::Vec2b(11, 10))
      {
        continue;
      }
      cv::Point oracle;
      opencv->getProjPixel(patterns, x, y, oracle);
      const cv::Vec2f p = result.projector.at<cv::Vec2f>(y, x);
      ++compared;
      disagree += (oracle.x != int(p[0]) || oracle.y != int(p[1])) ? 1 : 0;
    }
  }
  EXPECT_GT(compared, 1000);
  EXPECT_EQ(disagree, 0);
}

TEST(GrayCodeDecode, CapturesThatDoNotFitAreRefused)
{
  const int w = 64, h = 32;
  const std::vector<cv::Mat> good = frameImages(grayCodeFrames(w, h));
  std::vector<cv::Mat> captures = good;
  captures.pop_back();
  EXPECT_NE(decodeGrayCode(w, h, captures).error.find("23 captures for 24 frames"), std::string::npos)
      << decodeGrayCode(w, h, captures).error;
  EXPECT_FALSE(decodeGrayCode(w, h, {}).error.empty());
  captures = good;
  captures[5] = cv::Mat(h + 1, w, CV_8UC1, cv::Scalar(0));
  EXPECT_NE(decodeGrayCode(w, h, captures).error.find("capture 5 is 64x33"), std::string::npos)
      << decodeGrayCode(w, h, captures).error;
  captures = good;
  good[7].convertTo(captures[7], CV_16U);
  EXPECT_NE(decodeGrayCode(w, h, captures).error.find("capture 7 is not 8-bit grey"), std::string::npos);
  captures = good;
  cv::cvtColor(good[0], captures[0], cv::COLOR_GRAY2BGR);
  EXPECT_NE(decodeGrayCode(w, h, captures).error.find("capture 0 is not 8-bit grey"), std::string::npos);
  captures = good;
  captures[3] = cv::Mat();
  EXPECT_NE(decodeGrayCode(w, h, captures).error.find("capture 3 is empty"), std::string::npos);
  EXPECT_FALSE(decodeGrayCode(0, h, good).error.empty());
  EXPECT_FALSE(decodeGrayCode(w, -5, good).error.empty());
  GrayDecodeOptions options;
  options.min_bit_fraction = std::nan("");
  EXPECT_FALSE(decodeGrayCode(w, h, good, options).error.empty());
  options = GrayDecodeOptions();
  options.min_lit_contrast = 0;
  EXPECT_FALSE(decodeGrayCode(w, h, good, options).error.empty());
}

TEST(GrayCodeDecode, NothingLitDecodesNothingAndSaturationIsCounted)
{
  const int w = 64, h = 32;
  // A camera that sees no projector light: every frame the same ambient picture.
  const std::vector<cv::Mat> dark(2 + 2 * (6 + 5), cv::Mat(h, w, CV_8UC1, cv::Scalar(60)));
  const GrayDecodeResult nothing = decodeGrayCode(w, h, dark);
  ASSERT_TRUE(nothing.error.empty()) << nothing.error;
  EXPECT_EQ(nothing.lit, 0);
  EXPECT_EQ(nothing.decoded, 0);
  EXPECT_EQ(cv::countNonZero(nothing.projector.reshape(1) == nothing.projector.reshape(1)), 0);  // all NaN

  // Simulated camera with a strong gain: white saturates; pattern vs inverse still decodes.
  sim::Scene scene = sim::demoScene(false);
  scene.gain = 1.2;
  scene.supersample = 1;
  const sim::Camera camera(scene);
  std::vector<cv::Mat> captures;
  const std::vector<PatternFrame> frames = grayCodeFrames(1280, 800);
  for (std::size_t i = 0; i < frames.size(); ++i)
  {
    captures.push_back(camera.capture(frames[i].image, i));
  }
  const GrayDecodeResult bright = decodeGrayCode(1280, 800, captures);
  ASSERT_TRUE(bright.error.empty()) << bright.error;
  // Oracle: the white capture itself.
  cv::Mat lit = (captures[0] - captures[1]) >= 20;
  EXPECT_EQ(bright.lit, cv::countNonZero(lit));
  EXPECT_EQ(bright.saturated, cv::countNonZero(lit & (captures[0] >= 250)));
  EXPECT_GT(bright.saturated, bright.lit / 2);
  EXPECT_GT(bright.decoded, bright.lit * 8 / 10);
}

TEST(GrayCode, RestrictDecodeKeepsOnlyTheMaskedPixelsAndTheirEdges)
{
  GrayDecodeResult d;
  d.projector = cv::Mat(2, 4, CV_32FC2, cv::Scalar(10.0f, 20.0f));
  d.bits = cv::Mat(2, 4, CV_8UC2, cv::Scalar(5, 6));
  d.lit = d.decoded = d.full = 8;
  StripeEdge inside;  // between pixels (0, 0) and (1, 0)
  inside.x = 0.4f;
  StripeEdge across;  // between (1, 0) and (2, 0): (2, 0) is masked out
  across.x = 1.6f;
  StripeEdge outside;  // between (2, 1) and (3, 1)
  outside.x = 2.5f;
  outside.y = 1.0f;
  d.edges = {inside, across, outside};
  cv::Mat keep = cv::Mat::zeros(2, 4, CV_8UC1);
  keep(cv::Rect(0, 0, 2, 2)).setTo(255);  // the left half
  const GrayDecodeResult r = restrictDecode(d, keep);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.lit, 8);
  for (int y = 0; y < 2; ++y)
  {
    for (int x = 0; x < 4; ++x)
    {
      const bool kept = x < 2;
      EXPECT_EQ(std::isfinite(r.projector.at<cv::Vec2f>(y, x)[0]), kept) << x << "," << y;
      EXPECT_EQ(r.bits.at<cv::Vec2b>(y, x)[0], kept ? 5 : 0) << x << "," << y;
    }
  }
  ASSERT_EQ(r.edges.size(), 1u);
  EXPECT_FLOAT_EQ(r.edges[0].x, 0.4f);
  // The original is untouched; a mask of another size is an error.
  EXPECT_TRUE(std::isfinite(d.projector.at<cv::Vec2f>(0, 3)[0]));
  EXPECT_FALSE(restrictDecode(d, cv::Mat::zeros(3, 4, CV_8UC1)).error.empty());
}
}  // namespace
}  // namespace rviz_projector
