#include "brick_pose/segmentation/hsv_segmenter.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
void HsvSegmenterParams::validate() const
{
  if (min_area_px < 1) throw ConfigError("hsv segmenter: min_area_px must be >= 1");
  if (open_kernel_px < 0) throw ConfigError("hsv segmenter: open_kernel_px must be >= 0");
  if (close_kernel_px < 0) throw ConfigError("hsv segmenter: close_kernel_px must be >= 0");
}

HsvSegmenter::HsvSegmenter(const HsvSegmenterParams& params) : params_(params) { params_.validate(); }

cv::Mat HsvSegmenter::thresholdHsv(const cv::Mat& hsv, const HsvRange& range)
{
  cv::Mat mask;
  const cv::Scalar low(range.min[0], range.min[1], range.min[2]);
  const cv::Scalar high(range.max[0], range.max[1], range.max[2]);
  if (!range.wrapsHue())
  {
    cv::inRange(hsv, low, high, mask);
    return mask;
  }
  // Reds straddle hue 0: [min, 180] or [0, max].
  cv::Mat upper;
  cv::inRange(hsv, low, cv::Scalar(180, range.max[1], range.max[2]), mask);
  cv::inRange(hsv, cv::Scalar(0, range.min[1], range.min[2]), high, upper);
  cv::bitwise_or(mask, upper, mask);
  return mask;
}

void HsvSegmenter::cleanMask(cv::Mat& mask) const
{
  if (params_.open_kernel_px > 1)
    cv::morphologyEx(mask, mask, cv::MORPH_OPEN,
                     cv::getStructuringElement(cv::MORPH_RECT, {params_.open_kernel_px, params_.open_kernel_px}));
  if (params_.close_kernel_px > 1)
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_RECT, {params_.close_kernel_px, params_.close_kernel_px}));
}

std::vector<Segment> HsvSegmenter::components(const cv::Mat& mask, const cv::Mat& depth_m,
                                              const std::string& type_name) const
{
  cv::Mat labels, stats, centroids;
  const int label_count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<Segment> segments;
  for (int label = 1; label < label_count; ++label)
  {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < params_.min_area_px) continue;
    Segment segment;
    segment.type_name = type_name;
    segment.area_px = area;
    segment.bounding_box_px = cv::Rect(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                                       stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    const cv::Rect& box = segment.bounding_box_px;
    segment.mask = cv::Mat::zeros(box.size(), CV_8UC1);
    segment.pixel_indices.reserve(static_cast<std::size_t>(area));
    for (int v = box.y; v < box.y + box.height; ++v)
    {
      const int* label_row = labels.ptr<int>(v);
      const float* depth_row = depth_m.ptr<float>(v);
      std::uint8_t* mask_row = segment.mask.ptr<std::uint8_t>(v - box.y);
      for (int u = box.x; u < box.x + box.width; ++u)
      {
        if (label_row[u] != label) continue;
        mask_row[u - box.x] = 255;
        if (!std::isnan(depth_row[u])) segment.pixel_indices.push_back(v * mask.cols + u);
      }
    }
    segments.push_back(std::move(segment));
  }
  std::sort(segments.begin(), segments.end(),
            [](const Segment& a, const Segment& b) { return a.area_px > b.area_px; });
  return segments;
}

std::vector<Segment> HsvSegmenter::segment(const RgbdFrame& frame, const BrickCatalogue& catalogue) const
{
  cv::Mat hsv;
  cv::cvtColor(frame.rgb, hsv, cv::COLOR_RGB2HSV);
  std::vector<Segment> segments;
  for (const BrickType& type : catalogue.types())
  {
    cv::Mat mask = thresholdHsv(hsv, type.plate_hsv);
    // Most types are absent from most frames: skip the morphology and the
    // labelling when there cannot be a component large enough.
    if (cv::countNonZero(mask) < params_.min_area_px) continue;
    cleanMask(mask);
    std::vector<Segment> found = components(mask, frame.depth_m, type.name);
    std::move(found.begin(), found.end(), std::back_inserter(segments));
  }
  return segments;
}
}  // namespace brick_pose
