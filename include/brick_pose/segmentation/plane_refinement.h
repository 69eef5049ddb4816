#pragma once
// Pixel-accurate borders for planes found on cells (the refinement step of
// PEAC, our own formulation). Cells inside a plane (all eight neighbours in
// the same plane) keep the pixels that lie on it. Everything else (the
// plane's border cells, cells across a crease or an edge, cells with too few
// depths or not flat) is decided pixel by pixel: each plane grows from its
// inner cells over 4-connected pixels that lie on it within the noise, and a
// pixel reached by two planes goes to the one it is closer to, so a crease
// between two faces is cut where the two planes meet. Growth never crosses
// a pixel without depth, which keeps coplanar faces with a gap between them
// apart.

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

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// CV_32SC1 image of the frame's size: the plane index (into
/// `cell_planes.planes`) of each pixel, -1 for none. Pixels non-zero in
/// `excluded` (CV_8UC1 of the frame's size, or empty) get no plane.
cv::Mat refinePlaneLabels(const RgbdFrame& frame, const PixelRays& rays, const CellGrid& grid,
                          const CellPlanes& cell_planes, const DepthNoise& noise, const cv::Mat& excluded,
                          const PlaneRefinementParams& params, bool parallel);
}  // namespace brick_pose
