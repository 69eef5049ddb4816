#pragma once
// Colour-free segmentation (paper, "Region Growing Plane Segmentation"):
// PCL region growing on normals and smoothness, for boxes of unknown colour.
//
// The frame is thinned to the depth medians of square blocks (not a voxel
// grid), so every point keeps the pixel it came from; a block spans one
// angle at every resolution (strideFor). Normals come from
// integral images on that organised cloud. Region growing leaves out the
// border of each face (normals bend there) and splits noisy faces, so each
// region, largest first, is then flood-filled at full resolution over the
// pixels lying on its plane that no larger region has claimed.

#include <vector>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct RegionGrowingParams
{
  /// Angle a block of the thinned frame spans (mrad): 6 px at the D415's
  /// 1280x720 focal length (920 px), 4 at 848x480 and 640x480 (613 px), 3 on
  /// a Kinect's VGA (525 px). A block fixed in pixels doubled that angle at
  /// VGA, and the normals' window (normal_smoothing_size blocks) then
  /// spanned small boxes' tops whole: on the real mOSD scenes 11 of 41 tops.
  double block_angle_mrad = 6.52;
  double normal_smoothing_size = 8.0;    ///< Integral-image window, in strided pixels.
  double max_depth_change_factor = 0.02; ///< Normals are not smoothed across depth jumps larger than this x depth.
  int neighbours = 8;                    ///< k of the region-growing neighbourhood.
  double smoothness_threshold_deg = 6.0; ///< Max angle between neighbouring normals in one region.
  double curvature_threshold = 0.03;     ///< Points above this curvature do not seed/grow regions.
  int min_region_points = 30;            ///< Smaller regions are dropped (strided points).
  /// Full-resolution footprint: a pixel is on a region's plane within
  /// max(footprint_plane_distance_m, 3 sigma), sigma = depth_noise_at_1m_m * z^2.
  double footprint_plane_distance_m = 0.006;
  double depth_noise_at_1m_m = 0.0016;
  /// A region whose own pixels are mostly (more than this fraction) claimed
  /// by a larger footprint is a piece of the same face and is dropped.
  double max_footprint_overlap = 0.5;
  int min_area_px = 400;                 ///< Footprints smaller than this are dropped.

  void validate() const;  ///< Throws ConfigError naming the field.
};

class RegionGrowingSegmenter
{
public:
  explicit RegionGrowingSegmenter(const RegionGrowingParams& params = RegionGrowingParams());

  /// The block size (pixels) for a camera of focal length `fx_px`: the
  /// block angle's, but never so small that a `width_px` x `height_px`
  /// frame makes more than kMaxBlocks blocks (1280x720 in 6 px blocks
  /// makes 25600, 640x480 in 3 px blocks 34133).
  int strideFor(double fx_px, int width_px, int height_px) const;

  static constexpr double kMaxBlocks = 40000.0;

  /// Planar segments of the frame, largest first; type_name is empty.
  std::vector<Segment> segment(const RgbdFrame& frame) const;

  const RegionGrowingParams& params() const { return params_; }

private:
  RegionGrowingParams params_;
};
}  // namespace brick_pose
