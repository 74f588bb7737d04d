// Structured light for the camera calibration (issue 24): the frames the projector shows (white,
// black, OpenCV's Gray code patterns) and the decoding of the camera's captures into the projector
// pixel that lights each camera pixel.
//
// Frame order: 0 all white (255), 1 all black (0), then cv::structured_light::GrayCodePattern's
// images as its generate() returns them: for each column bit from the most significant down, the
// pattern then its inverse; then the same for the row bits. ceil(log2(width)) column bits and
// ceil(log2(height)) row bits (1280x800: 11 + 10 bits, 2 + 42 = 44 frames). A pattern pixel is white
// where the column's (row's) reflected binary Gray code has that bit set.
//
// Decoding (ours; OpenCV's getProjPixel is the test's oracle of the bit order):
//  - lit: white - black >= min_lit_contrast; other pixels are not decoded.
//  - per bit, from the most significant down: the bit is pattern > inverse; it is reliable when
//    |pattern - inverse| >= max(min_bit_contrast, min_bit_fraction * (white - black)). Decoding an
//    axis stops at the first unreliable bit: a camera coarser than the projector blurs the finest
//    stripes, and a camera pixel straddling a stripe edge sees both halves.
//  - the known top k bits of a Gray code fix the top k bits of the binary number (b_i is the XOR of
//    the Gray bits i and above), so they fix an aligned block of 2^(n - k) columns. The coordinate is
//    the block's centre (clipped to the image: a block reaching past width - 1 is cut at width - 1,
//    as no column there is lit). A pixel that stops at bit i straddles that bit's stripe edge, which
//    is exactly the centre of its block: the centre is the right guess, not just the middle one.
//  - a block starting at or beyond width (height) is not decoded (a code the projector never shows).
//  - stripe edges (sub-pixel): the block centres are quantised (a camera 4x coarser than the projector
//    decodes blocks of 4-8 pixels, and its regular pixel lattice aliases with the stripes, so the
//    error does not even average out locally). An edge is exact in projector coordinates: between two
//    neighbouring camera pixels (right or down) that share the top i bits of an axis and whose bit i
//    (pattern - inverse) has opposite signs, the bit's stripe edge - the centre of the shared block,
//    start + width / 2 - 0.5 - lies between them. Where: the zero crossing of (pattern - inverse) /
//    (white - black), linearly interpolated (the normalisation cancels uneven illumination and
//    reflectance; ambient light cancels in the difference). The swing |D_a - D_b| must reach
//    min_bit_contrast. Its camera point is unbiased for a symmetric blur: a Gray bit is a square wave
//    with equally spaced edges, antisymmetric about each - except near the rim of the lit area, so
//    edges within edge_margin camera pixels of an unlit pixel are dropped.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace rviz_projector
{
struct PatternFrame
{
  std::string name;  ///< "white", "black", "column bit 10 of 11 (MSB)", "column bit 10 of 11 (MSB) inverse", ...
  cv::Mat image;     ///< CV_8UC1, projector width x height
};

/// Number of Gray code bits of an axis of this many pixels: ceil(log2(pixels)) (0 for 1 pixel).
int grayCodeBits(int pixels);

/// The frames to show, in order (see the file comment). Empty when a size is not positive or beyond
/// 16384.
std::vector<PatternFrame> grayCodeFrames(int projector_width, int projector_height);

struct GrayDecodeOptions
{
  /// Least white - black (grey levels) of a pixel the projector lights. Ambient light and camera
  /// noise (a few levels) stay below it.
  int min_lit_contrast = 20;
  /// Least |pattern - inverse| (grey levels) of a reliable bit: several sigma of the difference of
  /// two noisy frames (sigma 2 levels each -> 2.8).
  int min_bit_contrast = 10;
  /// ... and at least this fraction of the pixel's white - black: a bright pixel's half-blurred
  /// stripe is not trusted just because it is bright.
  double min_bit_fraction = 0.2;
  /// A white frame at or above this (grey levels) is saturated (counted; still decoded: pattern and
  /// inverse are compared with each other, saturation only hides how much brighter one is).
  int saturation = 250;
  /// Also find the stripe edges (GrayDecodeResult::edges).
  bool find_edges = true;
  /// Only edges whose two pixels have every pixel within this many camera pixels lit: near the rim
  /// of the lit area (the projector image's border, a shadow) the blur mixes in darkness on one side
  /// only, which pulls the zero crossing (measured: 1-2 projector pixels). 3 = 3 sigma of a 1 px blur.
  int edge_margin = 3;
};

/// Where a stripe edge of the projector lies in the camera image (see the file comment).
struct StripeEdge
{
  float x = 0.0f;           ///< camera pixel, sub-pixel (OpenCV convention)
  float y = 0.0f;
  float coordinate = 0.0f;  ///< the projector coordinate of the edge (u for a column edge, v for a row edge)
  /// The other projector coordinate there (block centre of the neighbouring decoded pixel); NaN when
  /// neither pixel decoded it.
  float other = 0.0f;
  std::uint8_t axis = 0;    ///< 0: column edge (u known), 1: row edge (v known)
  std::uint8_t bit = 0;     ///< which Gray bit, counted from the MSB (0 = MSB)
};

struct GrayDecodeResult
{
  std::string error;  ///< non-empty: the captures do not fit (count, size, type, empty)
  /// CV_32FC2, camera size: the projector pixel (u, v) lighting each camera pixel, OpenCV's
  /// convention (integer = pixel centre), the centre of the decoded block; NaN where not decoded.
  cv::Mat projector;
  /// CV_8UC2: reliable bits used for u and for v per camera pixel; (0, 0) where not decoded.
  cv::Mat bits;
  int lit = 0;        ///< camera pixels with white - black >= min_lit_contrast
  int saturated = 0;  ///< lit pixels whose white frame is saturated
  int decoded = 0;    ///< pixels with u and v decoded (possibly with fewer bits)
  int full = 0;       ///< pixels decoded with every bit
  std::vector<StripeEdge> edges;  ///< with find_edges: every stripe edge crossing between neighbours
};

/// captures[i] is the camera frame (CV_8UC1, all the same size, not empty) taken while
/// grayCodeFrames()[i] was shown.
GrayDecodeResult decodeGrayCode(int projector_width, int projector_height, const std::vector<cv::Mat>& captures,
                                const GrayDecodeOptions& options = GrayDecodeOptions());

/// The decode restricted to the camera pixels where `keep` (CV_8UC1, the captures' size) is non-zero:
/// the others become undecoded (NaN, bits 0), and only the edges whose both neighbouring pixels
/// (either side of its sub-pixel position along its row or column) are kept remain. The counts
/// (lit, saturated, decoded, full) stay the original's. A `keep` of another size or type, or a
/// decode with an error, gives an error.
GrayDecodeResult restrictDecode(const GrayDecodeResult& decoded, const cv::Mat& keep);

/// Width of the block of projector pixels fixed by the top `bits` of an axis of `total` bits
/// (2^(total - bits)); the coordinate's uncertainty is +- half of it.
inline int grayBlockWidth(int total_bits, int bits) { return 1 << (total_bits - bits); }
}  // namespace rviz_projector
