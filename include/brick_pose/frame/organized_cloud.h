#pragma once
// Inverse projection of an RgbdFrame into point clouds (paper eq. 2-4):
// X = (u - cx) Z / fx, Y = (v - cy) Z / fy, Z = depth(u, v).

#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "brick_pose/frame/rgbd_frame.h"

namespace brick_pose
{
/// The organised XYZRGB cloud of the whole frame (width x height, point
/// index = v * width + u); holes are NaN points, so the cloud is not dense.
pcl::PointCloud<pcl::PointXYZRGB>::Ptr makeOrganizedCloud(const RgbdFrame& frame);

/// The same into an existing cloud, reusing its storage when it already has
/// the frame's size: a fresh 1280x720 cloud is 30 MB whose allocation and
/// first touch cost more than the inverse projection itself.
void fillOrganizedCloud(const RgbdFrame& frame, pcl::PointCloud<pcl::PointXYZRGB>& cloud);

/// The 3D points of the given pixels (index = v * width + u) that have
/// depth, in the given order; pixels without depth are skipped. When
/// `kept_pixels` is given it receives the pixel index of every output point.
pcl::PointCloud<pcl::PointXYZ>::Ptr backProjectPixels(const RgbdFrame& frame,
                                                      const std::vector<int>& pixel_indices,
                                                      std::vector<int>* kept_pixels = nullptr);

/// An organised cloud of every `stride`-th pixel in both directions
/// (width/stride x height/stride), NaN for holes. `source_pixels` (same size as
/// the cloud) receives the full-resolution pixel index of each point. Used to
/// keep the pixel footprint of colour-free segments without a voxel grid.
pcl::PointCloud<pcl::PointXYZ>::Ptr makeStridedCloud(const RgbdFrame& frame, int stride,
                                                     std::vector<int>& source_pixels);
/// An organised cloud of `block` x `block` pixel blocks: each point is the
/// median of the block's valid depths, back-projected through the block's
/// centre pixel (NaN when fewer than a quarter of the block has depth).
/// Unlike striding, it survives dense dropouts (sunlight) and averages noise;
/// the median does not blend the two sides of a depth edge. `source_pixels`
/// receives the centre pixel of each block.
pcl::PointCloud<pcl::PointXYZ>::Ptr makeBlockMedianCloud(const RgbdFrame& frame, int block,
                                                         std::vector<int>& source_pixels);
}  // namespace brick_pose
