#pragma once
// A segment: the pixels (and through them the organised-cloud points) that
// one segmenter believes belong to a single brick face.

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace brick_pose
{
struct Segment
{
  /// Brick type the colour matched (HSV); empty for colour-free segments.
  std::string type_name;
  /// Indices into the organised cloud / image (v * width + u) of the segment
  /// pixels that have depth.
  std::vector<int> pixel_indices;
  /// Pixel footprint: CV_8UC1, 255 inside, covering `bounding_box_px` of the
  /// image. Includes pixels without depth (the outline comes from the image).
  cv::Mat mask;
  cv::Rect bounding_box_px;
  /// Number of non-zero mask pixels.
  int area_px = 0;
};

/// The segment whose footprint is `mask_px` (CV_8UC1, non-zero inside) over
/// `box_px` of the image: its area and the indices of its pixels that have
/// depth in `depth_m` (CV_32FC1, NaN where none). Used when a segment is cut
/// into parts.
Segment segmentFromMask(const cv::Mat& mask_px, const cv::Rect& box_px, const cv::Mat& depth_m,
                        const std::string& type_name);

/// Same, with the box shrunk to the mask's non-zero pixels (the mask a
/// cropped copy). A part of a big segment (one brick of a merged row) is
/// then processed at its own size, not at its parent's. The same pixels, in
/// the same order; an empty mask keeps `box_px`.
Segment croppedSegmentFromMask(const cv::Mat& mask_px, const cv::Rect& box_px, const cv::Mat& depth_m,
                               const std::string& type_name);
}  // namespace brick_pose
