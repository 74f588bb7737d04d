// ProjectorCamera's Pattern topic (issue 24): an Image on /projector/pattern is shown 1:1 instead of
// the scene, acknowledged on /projector/pattern/shown once on screen, ended by a 0 x 0 image or the
// Timeout; wrong sizes and encodings are refused with a status and the scene keeps showing.
//
// Oracle: the raw bytes of the published pattern, compared with the pixels grabbed from the output
// window (X server) and with the Image output, pixel for pixel.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <QImage>
#include <rviz/display.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Header.h>

#include "rviz_projector/displays/projector_camera_display.h"
#include "rviz_projector/displays/projector_output_window.h"
#include "projector_test_fixture.h"

using rviz_projector_test::countColour;
using rviz_projector_test::ProjectorSceneTest;
using rviz_projector_test::Status;
using rviz_projector_test::Vec2;

namespace
{
const char* const kPatternTopic = "/projector/pattern";
const QRgb kGreen = qRgb(0, 255, 0);

/// A mono8 pattern with every pixel independent (seeded noise, bits 0/255 and greys), so that any
/// shift, flip, scaling or blending of one pixel shows.
sensor_msgs::Image noisePattern(unsigned w, unsigned h, const std::string& name, unsigned seed)
{
  sensor_msgs::Image image;
  image.header.frame_id = name;
  image.width = w;
  image.height = h;
  image.encoding = "mono8";
  image.step = w + 3;  // padded rows: the step must be honoured
  image.data.resize(std::size_t(image.step) * h);
  std::mt19937 random(seed);
  for (auto& byte : image.data)
  {
    byte = static_cast<std::uint8_t>(random() % 4 * 85);  // 0, 85, 170, 255: exact in 8 bits
  }
  return image;
}

/// Pixels that differ by more than 2 levels in a channel (-1: sizes differ).
int differing(const QImage& a, const QImage& b)
{
  if (a.size() != b.size())
  {
    return -1;
  }
  int wrong = 0;
  for (int y = 0; y < a.height(); ++y)
  {
    for (int x = 0; x < a.width(); ++x)
    {
      const QRgb p = a.pixel(x, y), q = b.pixel(x, y);
      wrong += std::abs(qRed(p) - qRed(q)) > 2 || std::abs(qGreen(p) - qGreen(q)) > 2 || std::abs(qBlue(p) - qBlue(q)) > 2;
    }
  }
  return wrong;
}

QImage fromImageMessage(const sensor_msgs::Image& msg)
{
  QImage image(int(msg.width), int(msg.height), QImage::Format_RGB32);
  const int channels = msg.encoding == "mono8" ? 1 : msg.encoding == "rgba8" || msg.encoding == "bgra8" ? 4 : 3;
  const bool bgr = msg.encoding == "bgr8" || msg.encoding == "bgra8";
  for (int v = 0; v < image.height(); ++v)
  {
    for (int u = 0; u < image.width(); ++u)
    {
      const std::uint8_t* p = &msg.data[std::size_t(v) * msg.step + std::size_t(u) * channels];
      const int r = channels == 1 ? p[0] : bgr ? p[2] : p[0];
      const int g = channels == 1 ? p[0] : p[1];
      const int b = channels == 1 ? p[0] : bgr ? p[0] : p[2];
      image.setPixel(u, v, qRgb(r, g, b));
    }
  }
  return image;
}
}  // namespace

class PatternTest : public ProjectorSceneTest
{
protected:
  void SetUp() override
  {
    ProjectorSceneTest::SetUp();
    pattern_pub_ = nh_.advertise<sensor_msgs::Image>(kPatternTopic, 10);
    shown_sub_ = nh_.subscribe<std_msgs::Header>(std::string(kPatternTopic) + "/shown", 100,
                                                 [this](const std_msgs::Header::ConstPtr& h) { shown_.push_back(*h); });
    addTarget(Vec2{1.0, 0.0}, 0.3);  // a scene: a green disc in the lit area
    ASSERT_TRUE(waitFor([&] { return pattern_pub_.getNumSubscribers() > 0 && shown_sub_.getNumPublishers() > 0; }))
        << "the display neither subscribed to " << kPatternTopic << " nor advertised its /shown";
    scene_ = grabWhen([&](const QImage& w) { return countColour(w, kGreen, 60) > 200; });
    ASSERT_GT(countColour(scene_, kGreen, 60), 200) << "the scene (a green disc) is not shown to begin with";
  }

  QImage part(const QImage& window) const { return imagePart(window); }

  /// Publishes `pattern` stamped `stamp` and waits for its acknowledgement.
  bool showAndWaitForAck(sensor_msgs::Image pattern, double stamp)
  {
    pattern.header.stamp = ros::Time(stamp);
    pattern_pub_.publish(pattern);
    return waitFor([&] {
      for (const auto& h : shown_)
      {
        if (h.stamp == pattern.header.stamp && h.frame_id == pattern.header.frame_id)
        {
          return true;
        }
      }
      return false;
    });
  }

  ros::Publisher pattern_pub_;
  ros::Subscriber shown_sub_;
  std::vector<std_msgs::Header> shown_;
  QImage scene_;
};

TEST_F(PatternTest, APatternIsShownPixelForPixelAndAcknowledgedOnlyOnceOnScreen)
{
  const sensor_msgs::Image pattern = noisePattern(info_.width, info_.height, "noise 1", 1);
  ASSERT_TRUE(showAndWaitForAck(pattern, 1001.0)) << "no /shown with the pattern's stamp and frame_id";
  // Acknowledged means on screen: the very first grab after it already shows the pattern.
  const QImage first = part(grab());
  ASSERT_EQ(first.size(), QSize(int(info_.width), int(info_.height))) << "the projector's image is not 1:1 here";
  EXPECT_EQ(differing(first, fromImageMessage(pattern)), 0) << "the first grab after /shown is not the pattern, pixel for pixel";
  EXPECT_EQ(countColour(first, kGreen, 60), 0) << "the scene shows through the pattern";
  const Status status = statusOf(projector_, "Pattern");
  EXPECT_TRUE(status.present && status.level == rviz::StatusProperty::Ok) << status.text.toStdString();
  EXPECT_TRUE(status.text.contains("noise 1")) << status.text.toStdString();

  // The next pattern replaces it; the acknowledgement carries its header.
  const sensor_msgs::Image second = noisePattern(info_.width, info_.height, "noise 2", 2);
  ASSERT_TRUE(showAndWaitForAck(second, 1002.0));
  EXPECT_EQ(differing(part(grab()), fromImageMessage(second)), 0);

  // 0 x 0 ends it: acknowledged, and the scene is back.
  sensor_msgs::Image end;
  end.header.frame_id = "end";
  ASSERT_TRUE(showAndWaitForAck(end, 1003.0)) << "the 0 x 0 image is not acknowledged";
  EXPECT_GT(countColour(grabWhen([&](const QImage& w) { return countColour(w, kGreen, 60) > 200; }), kGreen, 60), 200)
      << "the scene did not come back after the 0 x 0 image";
  EXPECT_FALSE(statusOf(projector_, "Pattern").present);
}

TEST_F(PatternTest, ColourPatternsKeepTheirChannelsInEveryEncoding)
{
  for (const std::string encoding : {"rgb8", "bgr8", "rgba8", "bgra8"})
  {
    const int channels = encoding.size() == 5 ? 4 : 3;
    sensor_msgs::Image image;
    image.header.frame_id = encoding;
    image.width = info_.width;
    image.height = info_.height;
    image.encoding = encoding;
    image.step = image.width * channels;
    image.data.resize(std::size_t(image.step) * image.height);
    // Thirds: red, green, blue from the left (in the encoding's own channel order).
    for (unsigned v = 0; v < image.height; ++v)
    {
      for (unsigned u = 0; u < image.width; ++u)
      {
        std::uint8_t* p = &image.data[std::size_t(v) * image.step + std::size_t(u) * channels];
        const int third = int(3 * u / image.width);
        const int r = third == 0 ? 255 : 0, g = third == 1 ? 255 : 0, b = third == 2 ? 255 : 0;
        const bool bgr = encoding[0] == 'b';
        p[0] = std::uint8_t(bgr ? b : r);
        p[1] = std::uint8_t(g);
        p[2] = std::uint8_t(bgr ? r : b);
        if (channels == 4)
          p[3] = 255;
      }
    }
    ASSERT_TRUE(showAndWaitForAck(image, 2000.0 + channels + (encoding[0] == 'b' ? 0.5 : 0.0))) << encoding;
    const QImage shown = part(grab());
    EXPECT_EQ(differing(shown, fromImageMessage(image)), 0) << encoding;
    EXPECT_EQ(shown.pixel(10, 10), qRgb(255, 0, 0)) << encoding << ": the left third is not red";
    EXPECT_EQ(shown.pixel(int(info_.width) / 2, 10), qRgb(0, 255, 0)) << encoding << ": the middle is not green";
    EXPECT_EQ(shown.pixel(int(info_.width) - 10, 10), qRgb(0, 0, 255)) << encoding << ": the right third is not blue";
  }
}

TEST_F(PatternTest, WrongSizeOrEncodingIsRefusedAndTheSceneStays)
{
  sensor_msgs::Image small = noisePattern(640, 400, "half size", 3);
  pattern_pub_.publish(small);
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Pattern").present; }));
  Status status = statusOf(projector_, "Pattern");
  EXPECT_EQ(status.level, rviz::StatusProperty::Error);
  EXPECT_TRUE(status.text.contains("640x400") && status.text.contains("1280x800")) << status.text.toStdString();
  EXPECT_GT(countColour(grab(), kGreen, 60), 200) << "a refused pattern blanked the scene";

  sensor_msgs::Image depth = noisePattern(info_.width, info_.height, "depth", 4);
  depth.encoding = "16UC1";
  pattern_pub_.publish(depth);
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Pattern").text.contains("16UC1"); }))
      << statusOf(projector_, "Pattern").text.toStdString();
  sensor_msgs::Image truncated = noisePattern(info_.width, info_.height, "truncated", 5);
  truncated.data.resize(truncated.data.size() / 2);
  pattern_pub_.publish(truncated);
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Pattern").text.contains("bytes"); }))
      << statusOf(projector_, "Pattern").text.toStdString();
  EXPECT_GT(countColour(grab(), kGreen, 60), 200);
  EXPECT_TRUE(shown_.empty()) << "a refused pattern was acknowledged";

  // A good one after them is shown.
  const sensor_msgs::Image good = noisePattern(info_.width, info_.height, "good", 6);
  ASSERT_TRUE(showAndWaitForAck(good, 3000.0));
  EXPECT_EQ(differing(part(grab()), fromImageMessage(good)), 0);
}

TEST_F(PatternTest, TheSceneComesBackAfterTheTimeout)
{
  projector_->subProp("Pattern topic")->subProp("Timeout")->setValue(0.5);
  const sensor_msgs::Image pattern = noisePattern(info_.width, info_.height, "left alone", 7);
  ASSERT_TRUE(showAndWaitForAck(pattern, 4000.0));
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Pattern").level == rviz::StatusProperty::Warn; }, 5.0));
  EXPECT_TRUE(statusOf(projector_, "Pattern").text.contains("0.5 s")) << statusOf(projector_, "Pattern").text.toStdString();
  EXPECT_GT(countColour(grabWhen([&](const QImage& w) { return countColour(w, kGreen, 60) > 200; }), kGreen, 60), 200)
      << "the scene did not come back after the timeout";
}

TEST_F(PatternTest, TheImageOutputCarriesThePatternAtOnce)
{
  std::vector<sensor_msgs::Image> images;
  ros::Subscriber sub = nh_.subscribe<sensor_msgs::Image>(
      "/projector/rendered/image", 10, [&](const sensor_msgs::Image::ConstPtr& m) { images.push_back(*m); });
  projector_->subProp("Image output")->subProp("Image rate")->setValue(0.2);  // one every 5 s at most
  projector_->subProp("Image output")->setValue(true);
  ASSERT_TRUE(waitFor([&] { return !images.empty(); }, 10.0)) << "no Image output";
  images.clear();
  const sensor_msgs::Image pattern = noisePattern(info_.width, info_.height, "to the camera", 8);
  ASSERT_TRUE(showAndWaitForAck(pattern, 5000.0));
  // Not after the Image rate's 5 s: a new pattern goes out with the frame that shows it.
  ASSERT_TRUE(waitFor([&] { return !images.empty(); }, 2.0)) << "the pattern was not published at once";
  EXPECT_EQ(differing(fromImageMessage(images.back()), fromImageMessage(pattern)), 0) << "the Image output is not the pattern";
}

TEST_F(PatternTest, ADistortingLensDoesNotWarpThePattern)
{
  sensor_msgs::CameraInfo distorted = info_;
  distorted.distortion_model = "plumb_bob";
  distorted.D = {-0.2, 0.05, 0.0, 0.0, 0.0};
  info_pub_.publish(distorted);
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Distortion").text.contains("warp"); }))
      << statusOf(projector_, "Distortion").text.toStdString();
  const sensor_msgs::Image pattern = noisePattern(info_.width, info_.height, "raw pixels", 9);
  ASSERT_TRUE(showAndWaitForAck(pattern, 6000.0));
  EXPECT_EQ(differing(part(grab()), fromImageMessage(pattern)), 0) << "the pattern went through the distortion warp";
}

TEST_F(PatternTest, AnEmptyTopicTurnsTheInterfaceOff)
{
  projector_->subProp("Pattern topic")->setValue("");
  ASSERT_TRUE(waitFor([&] { return pattern_pub_.getNumSubscribers() == 0; }));
  // Nobody listens any more: a pattern cannot reach the projector.
  pattern_pub_.publish(noisePattern(info_.width, info_.height, "ignored", 10));
  EXPECT_GT(countColour(grab(), kGreen, 60), 200);
  EXPECT_TRUE(shown_.empty());
}

TEST_F(PatternTest, AnEndWhileNoPatternIsShownIsAcknowledgedAtOnce)
{
  // Nothing changes on screen (the scene is already shown), so no frame is needed: the
  // acknowledgement must come anyway.
  sensor_msgs::Image end;
  end.header.frame_id = "end without a pattern";
  ASSERT_TRUE(showAndWaitForAck(end, 7000.0)) << "a 0 x 0 image while the scene is shown was not acknowledged";
}

TEST_F(PatternTest, AWindowThatScalesTheImageRefusesThePattern)
{
  // A 640x400 lens on the 1280x800 projector screen: the image is shown at twice its size.
  sensor_msgs::CameraInfo half = rviz_projector_test::projectorInfo(640, 400, 650, 319.5, 199.5);
  info_pub_.publish(half);
  ASSERT_TRUE(waitFor([&] { return projector_->hasLens() && projector_->lens().width() == 640u; }));
  pattern_pub_.publish(noisePattern(640, 400, "scaled", 11));
  ASSERT_TRUE(waitFor([&] { return statusOf(projector_, "Pattern").level == rviz::StatusProperty::Error; }))
      << statusOf(projector_, "Pattern").text.toStdString();
  const QString text = statusOf(projector_, "Pattern").text;
  EXPECT_TRUE(text.contains("640x400") && text.contains("1280x800") && text.contains("1:1")) << text.toStdString();
  EXPECT_TRUE(shown_.empty()) << "a scaled pattern was acknowledged";
}
