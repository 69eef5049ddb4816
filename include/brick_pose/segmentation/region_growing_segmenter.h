#pragma once
// Colour-free segmentation (paper, "Region Growing Plane Segmentation"):
// PCL region growing on normals and smoothness, for boxes of unknown colour.
//
// The frame is thinned by taking every `stride_px`-th pixel (not a voxel
// grid), so every point keeps the pixel it came from; normals come from
// integral images on that organised cloud. Region growing leaves out the
// border of each face (normals bend there), so each region's footprint is
// then regrown at full resolution over the pixels lying on the region's plane.

#include <vector>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct RegionGrowingParams
{
  int stride_px = 4;                     ///< Thinning of the frame before normals.
  double normal_smoothing_size = 6.0;    ///< Integral-image window, in strided pixels.
  double max_depth_change_factor = 0.02; ///< Normals are not smoothed across depth jumps larger than this x depth.
  int neighbours = 8;                    ///< k of the region-growing neighbourhood.
  double smoothness_threshold_deg = 5.0; ///< Max angle between neighbouring normals in one region.
  double curvature_threshold = 0.02;     ///< Points above this curvature do not seed/grow regions.
  int min_region_points = 40;            ///< Smaller regions are dropped (strided points).
  /// Full-resolution footprint: pixels within this distance of the region's
  /// plane and connected to the region join the segment.
  bool regrow_footprint = true;
  double footprint_plane_distance_m = 0.006;
  int min_area_px = 400;                 ///< Footprints smaller than this are dropped.
  /// A footprint sharing more than this fraction of its pixels with a larger
  /// one is the same face (split into two regions) and is dropped.
  double max_footprint_overlap = 0.5;

  void validate() const;  ///< Throws ConfigError naming the field.
};

class RegionGrowingSegmenter
{
public:
  explicit RegionGrowingSegmenter(const RegionGrowingParams& params = RegionGrowingParams());

  /// Planar segments of the frame, largest first; type_name is empty.
  std::vector<Segment> segment(const RgbdFrame& frame) const;

  const RegionGrowingParams& params() const { return params_; }

private:
  RegionGrowingParams params_;
};
}  // namespace brick_pose
