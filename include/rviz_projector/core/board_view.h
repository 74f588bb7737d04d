// A printed checkerboard propped up tilted on the floor, seen by the robot's camera (issue 24): the
// second plane that lets calibrate_projector --camera --board fit the projector's fx, fy, cx, cy
// (a flat floor alone cannot: see dense_mount_solver.h).
//
// findBoard: cv::findChessboardCorners + cv::cornerSubPix in the camera's white frame, cv::solvePnP
// with the camera's K and D -> the board's plane in the camera frame -> the base frame (the camera's
// tf). Only the plane is used (not the board's in-plane position), so the 180-degree ambiguity of a
// symmetric board does not matter. Masks of the camera image: the pixels on the board (the corners'
// outline grown by 3/4 of a square, so inside the printed squares) and the pixels near it that are
// kept out of the floor (the outline grown by 3 squares: the board's white margin, its silhouette
// against the floor, its stand).
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "rviz_projector/core/camera_floor.h"
#include "rviz_projector/core/lens_calibration.h"
#include "rviz_projector/core/rigid_transform.h"

namespace rviz_projector
{
/// A checkerboard: inner corners (cols x rows, as cv::findChessboardCorners counts them) and the
/// side of a square, metres.
struct BoardSpec
{
  int cols = 0;
  int rows = 0;
  double square = 0.0;
};

/// "" when the spec is usable: 3..50 inner corners each way, square 5 mm .. 0.5 m.
std::string boardSpecProblem(const BoardSpec& spec);

/// Parses "COLSxROWS:SQUARE_M" (e.g. "7x5:0.04"); false (with `error`) when malformed or refused by
/// boardSpecProblem.
bool parseBoardSpec(const std::string& text, BoardSpec& out, std::string& error);

struct BoardLimits
{
  /// Least angle between the board and the floor (degrees): a flatter board is almost the floor's
  /// plane again and pins the intrinsics no better.
  double min_tilt_deg = 15.0;
  /// Largest RMS reprojection error of the corners after solvePnP (camera pixels): more means a
  /// bent board, a wrong square size or a wrong camera calibration.
  double max_corner_rms_px = 1.0;
};

struct BoardView
{
  std::string error;                ///< the refusal, one sentence ("" when found)
  std::vector<cv::Point2f> corners; ///< camera pixels (raw image), findChessboardCorners' order
  Plane plane;                      ///< base frame, normal towards the camera
  double tilt_deg = 0.0;            ///< angle between the board and the plane z = 0
  double corner_rms_px = 0.0;       ///< RMS reprojection error of the corners
  double distance = 0.0;            ///< camera to the board's centre, metres
  cv::Mat on_board;                 ///< CV_8UC1 camera image: 255 on the printed squares
  cv::Mat near_board;               ///< CV_8UC1: 255 within 3 squares of them (not floor)
};

/// The board in the camera's white frame (CV_8UC1, the camera's size). camera: its CameraInfo
/// (cameraLensProblem must pass); base_T_camera: the camera's optical frame in the base frame.
BoardView findBoard(const cv::Mat& white, const LensCalibration& camera, const RigidTransform& base_T_camera,
                    const BoardSpec& spec, const BoardLimits& limits = BoardLimits());
}  // namespace rviz_projector
