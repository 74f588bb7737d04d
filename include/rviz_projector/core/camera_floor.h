// What the robot's camera sees on the floor (issue 24): camera pixels -> floor points, and decoded
// structured light -> projector pixel / floor point correspondences for the mount solver.
//
// Camera lens: a CameraInfo's raw image, K and D (plumb_bob or rational_polynomial, through
// cv::undistortPoints run to convergence). Binning other than 0/1 and a region of interest other
// than none (all zero) or the whole image are refused: the captures would be in a reduced image
// that K does not describe directly, and the robot's camera driver is expected to deliver full frames.
// K must be a plain camera matrix (no skew, last row 0 0 1); P and R are not used (raw, unrectified
// images). A D whose radial map folds back before the image corner is refused (LensDistortion).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rviz_projector/core/gray_code.h"
#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/mount_solver.h"
#include "rviz_projector/core/rigid_transform.h"
#include "rviz_projector/core/vec2.h"
#include "rviz_projector/core/vec3.h"

namespace rviz_projector
{
/// Problems of a camera lens for cameraPixelsOnPlane ("" when fine), see the file comment.
std::string cameraLensProblem(const LensCalibration& camera);

/// Floor points seen by camera pixels (raw image, OpenCV's convention: integer = pixel centre):
/// undistorted with K and D, the ray rotated into the base frame by base_T_camera_optical
/// (p_base = T.apply(p_optical)), intersected with z = plane_z. A ray that misses the plane (parallel
/// to it within 1e-9, or meeting it behind the camera) and a non-finite pixel give NaN. Errors (the
/// lens, a non-finite transform or plane) in `error`, with an empty result.
std::vector<Vec3> cameraPixelsOnPlane(const LensCalibration& camera, const RigidTransform& base_T_camera_optical,
                                      const std::vector<Vec2>& pixels, double plane_z, std::string& error);

/// A plane of the base frame: the points p with dot(normal, p) = offset (normal of unit length).
struct Plane
{
  Vec3 normal{0.0, 0.0, 1.0};
  double offset = 0.0;
};

/// cameraPixelsOnPlane on any plane (a tilted calibration board): as above, a ray parallel to it
/// within 1e-9 or meeting it behind the camera gives NaN; a normal not of unit length (within 1e-6)
/// or not finite is an error.
std::vector<Vec3> cameraPixelsOnPlane(const LensCalibration& camera, const RigidTransform& base_T_camera_optical,
                                      const std::vector<Vec2>& pixels, const Plane& plane, std::string& error);

struct CorrespondenceOptions
{
  /// Projector cell size, pixels: one correspondence per cell x cell block of projector pixels.
  int cell = 8;
  /// Least decoded camera pixels in a cell (after the rejections below); fewer: no correspondence.
  int min_samples = 3;
  /// The floor plane, base frame.
  double plane_z = 0.0;
  /// Set: the points lie on this plane instead of z = plane_z (a tilted board, board_view.h).
  std::optional<Plane> plane;
  /// Local fit radius, cells: a cell's camera point comes from least-squares affine maps camera pixel
  /// -> projector u (from the column stripe edges) and -> v (row stripe edges) fitted over the
  /// (2r + 1)^2 cells around it. 0: plain averaging of the cell's own decoded block centres (noisy and
  /// aliased, see floorCorrespondences; kept for comparison).
  int fit_radius = 2;
  /// A stripe edge further than this (projector pixels) from the first fit is rejected (a wrongly
  /// decoded bit, a reflection) and the fits are redone once.
  double outlier_tolerance = 3.0;
};

struct Correspondences
{
  std::string error;
  /// id = cell index (row-major: cell_row * cells_per_row + cell_column), pixel = projector pixel,
  /// world = floor point (base frame, z = plane_z).
  std::vector<FloorPoint> points;
  double coverage = 0.0;  ///< fraction of the projector image's cells with a correspondence
  int samples = 0;        ///< decoded camera pixels with blocks no wider than a cell
  int rejected = 0;       ///< stripe edges rejected as off the first fit
};

/**
 * Correspondences for the solver from a decode.
 *  - Support: per projector cell, the camera pixels decoded to blocks no wider than `cell` in u and v
 *    (a block is aligned to its width, so it lies in one cell; a wider one straddles cells and is
 *    not counted), grouped by the cell of their block centre. Cells with fewer than min_samples give
 *    nothing. Their mean camera pixel is where the camera sees the cell.
 *  - Why not plain averaging: a camera coarser than the projector decodes blocks of 4-8 projector
 *    pixels, so each pixel's block centre is off by up to half a block; the error is zero-mean, but
 *    the camera's regular lattice aliases with the stripes (a moire with periods of tens of
 *    projector pixels), so it does not average out over a cell, nor over a few cells (measured with
 *    the demo projector and a 640x480 camera: median 0.7-0.95 px, max 5 px). Unbiased and precise
 *    instead: the stripe edges (GrayDecodeResult::edges) are exact projector coordinates at
 *    sub-pixel camera points. Per cell, u = affine(camera x, y) is fitted to the column edges and
 *    v = affine(x, y) to the row edges of the (2r + 1)^2 cells around it (edges are assigned to
 *    cells by their exact coordinate and the other coordinate decoded beside them), edges off the
 *    first fit by more than outlier_tolerance are dropped and the fit redone; the two affine maps are
 *    solved for the camera point of the cell's centre pixel. The map camera -> projector is smooth
 *    (a homography bent by two lenses); an affine fit over ~40 projector pixels leaves a curvature
 *    error of a few hundredths of a pixel.
 *  - A fit that is ill-conditioned (fewer than 6 edges, edges along a line) or that puts the cell's
 *    centre more than 4 camera pixels from the cell's mean camera pixel gives no correspondence.
 *  - Output: pixel = the cell's centre ((first + last pixel) / 2 of the cell, cut at the image edge),
 *    world = the floor point of its camera point (cameraPixelsOnPlane). With fit_radius 0: pixel =
 *    mean of the cell's block centres, world = floor point of their mean camera pixel (the same
 *    camera point for both, so no pairing bias; the maps' curvature over one cell is negligible).
 * Errors: the decode's own error, projector/bits of the wrong type or size, a camera image size
 * (when given) that differs from the captures, options out of range, the camera lens.
 */
Correspondences floorCorrespondences(const GrayDecodeResult& decoded, const LensCalibration& camera,
                                     const RigidTransform& base_T_camera_optical, int projector_width,
                                     int projector_height, const CorrespondenceOptions& options = CorrespondenceOptions());
}  // namespace rviz_projector
