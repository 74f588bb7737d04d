// CameraSimulation: what a camera on the demo robot sees of the floor lit by the projector, for
// demo_camera (the demo's and the tests' stand-in for a real camera, issue 24 part 3).
//
// This is the world the projector calibration is checked against, so its geometry is written here
// on purpose without the project's core (no PinholeModel, LensDistortion, ProjectorMount, mount
// solver): plain rotation matrices and OpenCV's own lens functions (cv::undistortPoints,
// cv::projectPoints, cv::remap). ROS-free; demo_camera.cpp is the ROS glue.
//
// Conventions (the same as launch/projector.launch, written out again here):
//   mount      x y z in the base frame (x forward, y left, z up, REP-103), fixed-axis roll, pitch,
//              yaw: R_base_body = Rz(yaw) * Ry(pitch) * Rx(roll) (positive pitch: looking down);
//   optical    body -> optical by the standard rotation: optical z = body x (along the view),
//              optical x = -body y (right), optical y = -body z (down), quaternion
//              (x, y, z, w) = (-0.5, 0.5, -0.5, 0.5);
//   lens       pixel (u, v) with integer values at pixel centres (OpenCV's convention), K = fx fy cx
//              cy, D as OpenCV's (4, 5, 8 coefficients: plumb_bob k1 k2 p1 p2 [k3], or
//              rational_polynomial), the floor is z = 0 of the base frame.
//
// Image formation, per camera pixel: supersampling x supersampling sub-pixels (a box filter: stripes
// finer than a pixel blur realistically) -> undistort (camera K, D; iterated to 1e-10, checked by
// projecting back) -> ray in the base frame -> floor z = 0 -> projector pixel through the TRUE
// projector pose and lens (cv::projectPoints with its D) -> bilinear sample of the projector's
// luminance. The maps are computed once per projector image size; a frame is one cv::remap. Then
// intensity = ambient + gain * luminance (clipped) (grey levels / 255), a Gaussian blur of `blur`
// pixels (sigma; the lens' and sensor's blur), Gaussian noise of `noise` (sigma, grey levels / 255),
// rounded and clipped to 8 bits. A camera ray that misses the floor (above the horizon), a floor
// point behind the projector, outside its image, or outside the projector lens' own field of view
// (1.05 x the largest undistorted radius of its image border: beyond it a polynomial lens model
// may fold back into the image) is unlit: ambient only. No light falloff with distance or angle (the
// calibration only uses where light falls, not how bright).
//
// Optionally a printed checkerboard stands in the scene (BoardSettings, for calibrate_projector
// --board): a camera ray meets it before the floor behind it; the floor behind it as seen from the
// projector is in its shadow; its face lit only from its printed side; what it reflects is scaled
// by its albedo (white squares and margin, black squares) per sub-pixel. Plain ray-plane maths.
#pragma once

#include <opencv2/core.hpp>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

namespace rviz_projector_demo
{
/// A mount as projector.launch takes it (metres, radians; see the conventions above).
struct MountPose
{
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;
  double roll = 0.0;
  double pitch = 0.0;
  double yaw = 0.0;
};

/// A lens: pinhole K and OpenCV distortion D (empty: none).
struct LensParameters
{
  double fx = 0.0;
  double fy = 0.0;
  double cx = 0.0;
  double cy = 0.0;
  std::vector<double> D;
};

/// A printed checkerboard in the scene: its centre (the middle of its inner corners) and
/// orientation in the base frame as a mount (R = Rz(yaw) Ry(pitch) Rx(roll)); its own x along the
/// corner columns, y along the rows, z out of its printed face (roll = pitch = yaw = 0: flat on its
/// back, face up; pitch -0.785: standing 45 deg, facing -x). cols x rows inner corners, squares of
/// `square` metres, a white `margin` (metres) around the squares.
struct BoardSettings
{
  bool present = false;
  MountPose pose;
  int cols = 7;
  int rows = 5;
  double square = 0.06;
  double margin = 0.03;
  double white = 0.85;  ///< albedo of the white squares and the margin (the floor's is 1)
  double black = 0.08;
};

/// R_base_optical: columns are the optical frame's axes in the base frame.
cv::Matx33d opticalRotation(const MountPose& mount);

struct CameraSimulationSettings
{
  int width = 640;  ///< camera image, pixels
  int height = 480;
  LensParameters camera;
  MountPose camera_mount;
  LensParameters projector;  ///< the TRUE projector (the image size is the received image's)
  MountPose projector_mount;
  int supersampling = 3;  ///< sub-pixels per camera pixel and axis, 1..4
  double ambient = 0.2;   ///< floor brightness without projector light, 0..1
  /// What a white projector pixel adds on the floor, 0..10 of full scale (the camera's exposure:
  /// ambient + gain above 1 saturates). 0.7 keeps white (0.9 with the default ambient) below clipping.
  double gain = 0.7;
  double blur = 1.0;      ///< Gaussian blur sigma, camera pixels (0: none)
  double noise = 2.0 / 255.0;  ///< Gaussian noise sigma, grey levels / 255
  BoardSettings board;         ///< none unless present
};

/// "" when usable, else one sentence per problem (finite numbers, positive focal lengths, D of 0, 4,
/// 5 or 8 values, image size 1..8192, supersampling 1..4, ambient in [0, 1], blur and noise >= 0,
/// a camera above the floor; a board's corners 3..50 each way, square 0.005..0.5 m, margin 0..1 m,
/// albedos in [0, 1], its pose finite).
std::string checkSettings(const CameraSimulationSettings& settings);

/// The projector image's luminance (CV_8UC1, a copy): mono8 as is; rgb8/bgr8/rgba8/bgra8 as
/// 0.299 R + 0.587 G + 0.114 B (Rec. 601, OpenCV's cvtColor); alpha ignored. Returns "" or why the
/// image is refused (its encoding, a zero or over 8192 size, a row step or data size that does not
/// match): then `luminance` is left empty.
std::string projectorLuminance(const std::string& encoding, int width, int height, std::size_t step,
                               const std::uint8_t* data, std::size_t size, cv::Mat& luminance);

class CameraSimulation
{
public:
  /// `settings` must pass checkSettings (else std::invalid_argument with its message).
  explicit CameraSimulation(const CameraSimulationSettings& settings);

  /// The noise-free camera image (CV_32FC1, grey levels 0..255, blurred) of the floor lit by
  /// `luminance` (CV_8UC1 projector image; empty: no projector light, the ambient floor). Computes
  /// the maps when the projector's size changed.
  cv::Mat renderClean(const cv::Mat& luminance);

  /// A frame: `clean` plus noise from `rng`, rounded and clipped to CV_8UC1.
  cv::Mat expose(const cv::Mat& clean, cv::RNG& rng) const;

  /// Largest camera-pixel error of the undistortion, measured by projecting the undistorted rays
  /// back (after the first renderClean with a projector image; -1 before).
  double undistortionResidual() const { return undistortion_residual_; }
  /// Fraction of the camera's sub-pixels that see the projector's image (after a map was built).
  double litFraction() const { return lit_fraction_; }

private:
  void buildMaps(const cv::Size& projector_size);

  CameraSimulationSettings settings_;
  cv::Size projector_size_;
  cv::Mat map1_;  // fixed-point remap maps (cv::convertMaps) of the supersampled camera image
  cv::Mat map2_;
  cv::Rect lit_rect_;  // the sub-pixels that can see the projector (whole camera pixels)
  cv::Mat sub_;        // the supersampled luminance, black outside lit_rect_
  cv::Mat albedo_;     // with a board: CV_32FC1 supersampled albedo (1 on the floor), else empty
  double undistortion_residual_ = -1.0;
  double lit_fraction_ = 0.0;
};

/// The projector images received, with their arrival times (s): the one a frame exposed at t shows
/// is the newest that arrived at or before t - exposure_delay.
class ExposureHistory
{
public:
  struct Entry
  {
    double arrival = 0.0;
    cv::Mat luminance;
  };

  /// At most `capacity` images are kept (the oldest go first).
  explicit ExposureHistory(std::size_t capacity = 64) : capacity_(capacity) {}

  void add(double arrival, const cv::Mat& luminance);
  /// The newest image that arrived at or before `time`, or nullptr (none yet). Images older than
  /// it are dropped: later frames never need them.
  const Entry* at(double time);
  /// The newest image received (whatever its arrival), or nullptr.
  const Entry* newest() const { return entries_.empty() ? nullptr : &entries_.back(); }
  /// Time jumped back (a bag loop, a simulator reset): only the newest image is kept, shown from now.
  void restart();
  std::size_t size() const { return entries_.size(); }

private:
  std::size_t capacity_;
  std::deque<Entry> entries_;
};
}  // namespace rviz_projector_demo
