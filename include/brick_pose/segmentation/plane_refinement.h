#pragma once
// Pixel-accurate borders for planes found on cells (the refinement step of
// PEAC, our own formulation). Cells inside a plane (no other plane among
// their eight neighbours) keep the pixels that lie on it. Everything else
// (cells next to another plane, cells across a crease or an edge, cells
// with too few depths or not flat) is decided pixel by pixel: each plane
// grows from its inner cells over 4-connected pixels that lie on it within
// the noise, and a pixel reached by two planes goes to the one it and its
// neighbours are closer to, so a crease between two faces is cut where the
// two planes meet. Growth never crosses a pixel without depth, which keeps
// coplanar faces with a gap between them apart.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/segmentation/cell_clustering.h"
#include "brick_pose/segmentation/cell_grid.h"
#include "brick_pose/segmentation/depth_noise.h"

namespace brick_pose
{
struct PlaneRefinementParams
{
  /// A pixel is on a plane within this many noise sigmas at its depth ...
  double pixel_sigma_factor = 2.5;
  /// ... plus this (surfaces flat to a millimetre).
  double pixel_floor_m = 0.001;
  /// A pixel two planes reach goes to the one the pixels within this radius
  /// are closer to (0: the pixel alone decides).
  int contest_radius_px = 2;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// Writes into `labels` (made CV_32SC1 of the frame's size; its storage is
/// reused when it already has that size) the plane index (into
/// `cell_planes.planes`) of each pixel, -1 for none. Pixels non-zero in
/// `excluded` (CV_8UC1 of the frame's size, or empty) get no plane.
/// `inner_cells` (optional) receives 1 for each cell whose pixels were
/// decided by its own plane alone.
void refinePlaneLabels(const RgbdFrame& frame, const PixelRays& rays, const CellGrid& grid,
                       const CellPlanes& cell_planes, const DepthNoise& noise, const cv::Mat& excluded,
                       const PlaneRefinementParams& params, bool parallel, cv::Mat& labels,
                       std::vector<std::uint8_t>* inner_cells = nullptr);

/// Where the pixels of two planes touch in `labels` (from
/// refinePlaneLabels): 4-neighbouring pixel pairs, and the points on either
/// side. Only cells not in `inner_cells` are scanned (with one pixel beyond
/// their right and bottom sides): two planes cannot touch inside an inner
/// cell.
std::vector<PlaneSeam> planeBorders(const RgbdFrame& frame, const PixelRays& rays, const CellGrid& grid,
                                      const cv::Mat& labels, const std::vector<std::uint8_t>& inner_cells);
}  // namespace brick_pose
