#include "brick_pose/segmentation/segment.h"

#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
Segment segmentFromMask(const cv::Mat& mask_px, const cv::Rect& box_px, const cv::Mat& depth_m,
                        const std::string& type_name)
{
  Segment segment;
  segment.type_name = type_name;
  segment.bounding_box_px = box_px;
  segment.mask = mask_px;
  for (int y = 0; y < box_px.height; ++y)
  {
    const std::uint8_t* mask_row = mask_px.ptr<std::uint8_t>(y);
    const int v = y + box_px.y;
    const float* depth_row = depth_m.ptr<float>(v);
    for (int x = 0; x < box_px.width; ++x)
    {
      if (!mask_row[x]) continue;
      ++segment.area_px;
      const int u = x + box_px.x;
      if (!std::isnan(depth_row[u])) segment.pixel_indices.push_back(v * depth_m.cols + u);
    }
  }
  return segment;
}

Segment croppedSegmentFromMask(const cv::Mat& mask_px, const cv::Rect& box_px, const cv::Mat& depth_m,
                               const std::string& type_name)
{
  const cv::Rect used = cv::boundingRect(mask_px);  // of the non-zero pixels
  if (used.area() == 0) return segmentFromMask(mask_px, box_px, depth_m, type_name);
  return segmentFromMask(mask_px(used).clone(), used + box_px.tl(), depth_m, type_name);
}
}  // namespace brick_pose
