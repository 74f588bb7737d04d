// Gray code frames (OpenCV structured_light) and their decoding; see gray_code.h.
#include "rviz_projector/core/gray_code.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <opencv2/imgproc.hpp>
#include <opencv2/structured_light.hpp>

namespace rviz_projector
{
namespace
{
constexpr int kMaxProjectorSize = 16384;

bool sizeOk(int pixels) { return pixels >= 2 && pixels <= kMaxProjectorSize; }

std::string bitName(const char* axis, int bit, int bits)
{
  std::ostringstream name;
  name << axis << " bit " << bit << " of " << bits;
  if (bit == bits - 1)
  {
    name << " (MSB)";
  }
  else if (bit == 0)
  {
    name << " (LSB)";
  }
  return name.str();
}

void addAxisNames(const char* axis, int bits, std::vector<std::string>& names)
{
  for (int bit = bits - 1; bit >= 0; --bit)
  {
    names.push_back(bitName(axis, bit, bits));
    names.push_back(bitName(axis, bit, bits) + " inverse");
  }
}

struct AxisDecode
{
  int bits = 0;        ///< reliable bits
  int binary = 0;      ///< the binary number of those top bits
  float coordinate = std::numeric_limits<float>::quiet_NaN();
};

/// Decodes one axis of one camera pixel: `pattern` points at the pixel's value in each of the axis's
/// frames (pattern, inverse, pattern, inverse, ... MSB first).
AxisDecode decodeAxis(const uchar* const* frames, int x, int total_bits, int size, int threshold)
{
  AxisDecode out;
  int binary = 0;
  int previous = 0;
  for (int k = 0; k < total_bits; ++k)
  {
    const int difference = int(frames[2 * k][x]) - int(frames[2 * k + 1][x]);
    if (std::abs(difference) < threshold)
    {
      break;
    }
    const int gray = difference > 0 ? 1 : 0;
    previous ^= gray;  // binary bit = XOR of the Gray bits down to it
    binary = (binary << 1) | previous;
    ++out.bits;
  }
  out.binary = binary;
  if (out.bits == 0)
  {
    return out;
  }
  const int width = 1 << (total_bits - out.bits);
  const int start = binary << (total_bits - out.bits);
  if (start >= size)
  {
    out.bits = 0;
    return out;
  }
  const int end = std::min(start + width - 1, size - 1);
  out.coordinate = 0.5f * float(start + end);
  return out;
}
/// Per camera pixel and axis: reliable bits and their binary number (0 bits where not lit).
struct AxisCode
{
  cv::Mat bits;    ///< CV_8UC2
  cv::Mat binary;  ///< CV_32SC2
};

/// The stripe edges between pixel a and its neighbour b on one axis (see gray_code.h).
void edgesBetween(const std::vector<cv::Mat>& captures, const AxisCode& code, int axis, int first_frame,
                  int total_bits, int size, cv::Point a, cv::Point b, const cv::Mat& projector, int min_lit,
                  int min_swing, std::vector<StripeEdge>& edges)
{
  const int na = code.bits.at<cv::Vec2b>(a)[axis], nb = code.bits.at<cv::Vec2b>(b)[axis];
  const int ba = code.binary.at<cv::Vec2i>(a)[axis], bb = code.binary.at<cv::Vec2i>(b)[axis];
  const int last = std::min({na, nb, total_bits - 1});
  const double contrast_a = double(captures[0].at<uchar>(a)) - double(captures[1].at<uchar>(a));
  const double contrast_b = double(captures[0].at<uchar>(b)) - double(captures[1].at<uchar>(b));
  if (contrast_a < min_lit || contrast_b < min_lit)
  {
    return;
  }
  for (int i = 0; i <= last; ++i)
  {
    const int prefix = i == 0 ? 0 : (ba >> (na - i));
    if (i > 0 && prefix != (bb >> (nb - i)))
    {
      return;  // different blocks: no edge of a finer bit lies between them either
    }
    const cv::Mat& pattern = captures[std::size_t(first_frame + 2 * i)];
    const cv::Mat& inverse = captures[std::size_t(first_frame + 2 * i + 1)];
    const int da = int(pattern.at<uchar>(a)) - int(inverse.at<uchar>(a));
    const int db = int(pattern.at<uchar>(b)) - int(inverse.at<uchar>(b));
    if ((da > 0) == (db > 0) || da == 0 || db == 0 || std::abs(da - db) < min_swing)
    {
      continue;
    }
    const int width = 1 << (total_bits - i);
    const int edge_start = (prefix << (total_bits - i)) + width / 2;  // first column right of the edge
    if (edge_start >= size)
    {
      continue;  // the edge's far side is beyond the image (never lit)
    }
    const double na_ = da / contrast_a, nb_ = db / contrast_b;
    const double t = na_ / (na_ - nb_);
    StripeEdge edge;
    edge.x = float(a.x + t * (b.x - a.x));
    edge.y = float(a.y + t * (b.y - a.y));
    edge.coordinate = float(edge_start) - 0.5f;
    const int other = 1 - axis;
    const float oa = projector.at<cv::Vec2f>(a)[other], ob = projector.at<cv::Vec2f>(b)[other];
    edge.other = std::isfinite(oa) ? oa : ob;
    edge.axis = std::uint8_t(axis);
    edge.bit = std::uint8_t(i);
    edges.push_back(edge);
  }
}
}  // namespace

int grayCodeBits(int pixels)
{
  int bits = 0;
  while (bits < 31 && (1 << bits) < pixels)
  {
    ++bits;
  }
  return bits;
}

std::vector<PatternFrame> grayCodeFrames(int projector_width, int projector_height)
{
  std::vector<PatternFrame> frames;
  if (!sizeOk(projector_width) || !sizeOk(projector_height))
  {
    return frames;
  }
  cv::Ptr<cv::structured_light::GrayCodePattern> pattern =
      cv::structured_light::GrayCodePattern::create(projector_width, projector_height);
  std::vector<cv::Mat> images;
  pattern->generate(images);
  std::vector<std::string> names;
  addAxisNames("column", grayCodeBits(projector_width), names);
  addAxisNames("row", grayCodeBits(projector_height), names);
  if (images.size() != names.size())
  {
    return frames;  // OpenCV counts bits differently: nothing we could name (never seen)
  }
  frames.push_back({"white", cv::Mat(projector_height, projector_width, CV_8UC1, cv::Scalar(255))});
  frames.push_back({"black", cv::Mat(projector_height, projector_width, CV_8UC1, cv::Scalar(0))});
  for (std::size_t i = 0; i < images.size(); ++i)
  {
    frames.push_back({names[i], images[i]});
  }
  return frames;
}

GrayDecodeResult decodeGrayCode(int projector_width, int projector_height, const std::vector<cv::Mat>& captures,
                                const GrayDecodeOptions& options)
{
  GrayDecodeResult result;
  if (!sizeOk(projector_width) || !sizeOk(projector_height))
  {
    result.error = "projector size " + std::to_string(projector_width) + "x" + std::to_string(projector_height) +
                   " is not 2..16384 pixels in each direction";
    return result;
  }
  if (options.min_lit_contrast < 1 || options.min_lit_contrast > 255 || options.min_bit_contrast < 1 ||
      options.min_bit_contrast > 255 || !(options.min_bit_fraction >= 0.0 && options.min_bit_fraction <= 1.0) ||
      options.saturation < 1 || options.saturation > 255 || options.edge_margin < 0 || options.edge_margin > 64)
  {
    result.error = "decode options out of range (contrasts and saturation 1..255 grey levels, fraction 0..1, "
                   "edge margin 0..64 pixels)";
    return result;
  }
  const int column_bits = grayCodeBits(projector_width);
  const int row_bits = grayCodeBits(projector_height);
  const std::size_t expected = 2 + 2 * std::size_t(column_bits + row_bits);
  if (captures.size() != expected)
  {
    result.error = std::to_string(captures.size()) + " captures for " + std::to_string(expected) +
                   " frames (white, black, " + std::to_string(2 * column_bits) + " column and " +
                   std::to_string(2 * row_bits) + " row patterns)";
    return result;
  }
  for (std::size_t i = 0; i < captures.size(); ++i)
  {
    const cv::Mat& capture = captures[i];
    if (capture.empty())
    {
      result.error = "capture " + std::to_string(i) + " is empty";
      return result;
    }
    if (capture.type() != CV_8UC1)
    {
      result.error = "capture " + std::to_string(i) + " is not 8-bit grey (CV_8UC1, type " +
                     std::to_string(capture.type()) + ")";
      return result;
    }
    if (capture.size() != captures[0].size())
    {
      result.error = "capture " + std::to_string(i) + " is " + std::to_string(capture.cols) + "x" +
                     std::to_string(capture.rows) + ", capture 0 is " + std::to_string(captures[0].cols) + "x" +
                     std::to_string(captures[0].rows);
      return result;
    }
  }

  const int rows = captures[0].rows;
  const int cols = captures[0].cols;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  result.projector.create(rows, cols, CV_32FC2);
  result.projector.setTo(cv::Scalar(nan, nan));
  result.bits = cv::Mat::zeros(rows, cols, CV_8UC2);
  AxisCode code;
  code.bits = cv::Mat::zeros(rows, cols, CV_8UC2);
  code.binary = cv::Mat::zeros(rows, cols, CV_32SC2);
  std::vector<const uchar*> column_frames(2 * std::size_t(column_bits));
  std::vector<const uchar*> row_frames(2 * std::size_t(row_bits));
  for (int y = 0; y < rows; ++y)
  {
    const uchar* white = captures[0].ptr<uchar>(y);
    const uchar* black = captures[1].ptr<uchar>(y);
    for (std::size_t i = 0; i < column_frames.size(); ++i)
    {
      column_frames[i] = captures[2 + i].ptr<uchar>(y);
    }
    for (std::size_t i = 0; i < row_frames.size(); ++i)
    {
      row_frames[i] = captures[2 + column_frames.size() + i].ptr<uchar>(y);
    }
    cv::Vec2f* projector = result.projector.ptr<cv::Vec2f>(y);
    cv::Vec2b* bits = result.bits.ptr<cv::Vec2b>(y);
    cv::Vec2b* axis_bits = code.bits.ptr<cv::Vec2b>(y);
    cv::Vec2i* axis_binary = code.binary.ptr<cv::Vec2i>(y);
    for (int x = 0; x < cols; ++x)
    {
      const int contrast = int(white[x]) - int(black[x]);
      if (contrast < options.min_lit_contrast)
      {
        continue;
      }
      ++result.lit;
      if (white[x] >= options.saturation)
      {
        ++result.saturated;
      }
      const int threshold =
          std::max(options.min_bit_contrast, int(std::ceil(options.min_bit_fraction * double(contrast))));
      const AxisDecode u = decodeAxis(column_frames.data(), x, column_bits, projector_width, threshold);
      const AxisDecode v = decodeAxis(row_frames.data(), x, row_bits, projector_height, threshold);
      axis_bits[x] = cv::Vec2b(uchar(u.bits), uchar(v.bits));
      axis_binary[x] = cv::Vec2i(u.binary, v.binary);
      if (u.bits == 0 || v.bits == 0)
      {
        continue;
      }
      projector[x] = cv::Vec2f(u.coordinate, v.coordinate);
      bits[x] = cv::Vec2b(uchar(u.bits), uchar(v.bits));
      ++result.decoded;
      if (u.bits == column_bits && v.bits == row_bits)
      {
        ++result.full;
      }
    }
  }
  if (options.find_edges)
  {
    // Pixels with every pixel within edge_margin lit (outside the image counts as unlit).
    cv::Mat lit = (cv::Mat(captures[0]) - cv::Mat(captures[1])) >= options.min_lit_contrast;
    if (options.edge_margin > 0)
    {
      cv::erode(lit, lit, cv::Mat(), cv::Point(-1, -1), options.edge_margin, cv::BORDER_CONSTANT, cv::Scalar(0));
    }
    const int first_row_frame = 2 + 2 * column_bits;
    for (int y = 0; y < rows; ++y)
    {
      for (int x = 0; x < cols; ++x)
      {
        for (const cv::Point b : {cv::Point(x + 1, y), cv::Point(x, y + 1)})
        {
          if (b.x >= cols || b.y >= rows || !lit.at<uchar>(y, x) || !lit.at<uchar>(b))
          {
            continue;
          }
          const cv::Point a(x, y);
          edgesBetween(captures, code, 0, 2, column_bits, projector_width, a, b, result.projector,
                       options.min_lit_contrast, options.min_bit_contrast, result.edges);
          edgesBetween(captures, code, 1, first_row_frame, row_bits, projector_height, a, b, result.projector,
                       options.min_lit_contrast, options.min_bit_contrast, result.edges);
        }
      }
    }
  }
  return result;
}
}  // namespace rviz_projector

namespace rviz_projector
{
GrayDecodeResult restrictDecode(const GrayDecodeResult& decoded, const cv::Mat& keep)
{
  GrayDecodeResult out;
  if (!decoded.error.empty())
  {
    out.error = decoded.error;
    return out;
  }
  if (keep.type() != CV_8UC1 || keep.size() != decoded.projector.size() || decoded.bits.size() != keep.size())
  {
    out.error = "the pixel mask is not CV_8UC1 of the captures' size";
    return out;
  }
  out.lit = decoded.lit;
  out.saturated = decoded.saturated;
  out.decoded = decoded.decoded;
  out.full = decoded.full;
  out.projector = decoded.projector.clone();
  out.bits = decoded.bits.clone();
  const cv::Vec2f nan(std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::quiet_NaN());
  for (int y = 0; y < keep.rows; ++y)
  {
    const uchar* k = keep.ptr<uchar>(y);
    cv::Vec2f* projector = out.projector.ptr<cv::Vec2f>(y);
    cv::Vec2b* bits = out.bits.ptr<cv::Vec2b>(y);
    for (int x = 0; x < keep.cols; ++x)
    {
      if (k[x] == 0)
      {
        projector[x] = nan;
        bits[x] = cv::Vec2b(0, 0);
      }
    }
  }
  const auto kept = [&](double x, double y) {
    const int ix = int(x), iy = int(y);
    return ix >= 0 && iy >= 0 && ix < keep.cols && iy < keep.rows && keep.at<uchar>(iy, ix) != 0;
  };
  for (const StripeEdge& e : decoded.edges)
  {
    if (std::isfinite(e.x) && std::isfinite(e.y) && kept(std::floor(e.x), std::floor(e.y)) &&
        kept(std::ceil(e.x), std::ceil(e.y)))
    {
      out.edges.push_back(e);
    }
  }
  return out;
}
}  // namespace rviz_projector
