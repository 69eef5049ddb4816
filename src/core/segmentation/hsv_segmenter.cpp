#include "brick_pose/segmentation/hsv_segmenter.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/common/parallel_for.h"

namespace brick_pose
{
void HsvSegmenterParams::validate() const
{
  if (min_area_px < 1) throw ConfigError("hsv segmenter: min_area_px must be >= 1");
  if (open_kernel_px < 0) throw ConfigError("hsv segmenter: open_kernel_px must be >= 0");
  if (close_kernel_px < 0) throw ConfigError("hsv segmenter: close_kernel_px must be >= 0");
  if (coarse_factor < 1) throw ConfigError("hsv segmenter: coarse_factor must be >= 1");
  if (!(depth_jump_m >= 0.0)) throw ConfigError("hsv segmenter: depth_jump_m must be >= 0");
  if (worker_threads < 1) throw ConfigError("hsv segmenter: worker_threads must be >= 1");
}

HsvSegmenter::HsvSegmenter(const HsvSegmenterParams& params) : params_(params) { params_.validate(); }

namespace
{
std::size_t totalSize(const std::vector<std::vector<Segment>>& groups)
{
  std::size_t total = 0;
  for (const std::vector<Segment>& group : groups) total += group.size();
  return total;
}
}  // namespace

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

std::vector<Segment> HsvSegmenter::components(const cv::Mat& mask, const cv::Mat& depth_m, const std::string& type_name,
                                              const cv::Rect& roi_px, int image_width_px) const
{
  cv::Mat labels, stats, centroids;
  const int label_count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  // Reserved: a vector of segments that grows copies them (cv::Mat's move
  // is not noexcept), pixel lists and all.
  std::vector<Segment> segments;
  int kept = 0;
  for (int label = 1; label < label_count; ++label) kept += stats.at<int>(label, cv::CC_STAT_AREA) >= params_.min_area_px;
  segments.reserve(static_cast<std::size_t>(kept));
  for (int label = 1; label < label_count; ++label)
  {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < params_.min_area_px) continue;
    const cv::Rect local_box(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                             stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    Segment segment;
    segment.type_name = type_name;
    segment.area_px = area;
    segment.bounding_box_px = local_box + roi_px.tl();
    segment.mask = cv::Mat::zeros(local_box.size(), CV_8UC1);
    segment.pixel_indices.reserve(static_cast<std::size_t>(area));
    for (int y = local_box.y; y < local_box.y + local_box.height; ++y)
    {
      const int* label_row = labels.ptr<int>(y);
      const int v = y + roi_px.y;
      const float* depth_row = depth_m.ptr<float>(v);
      std::uint8_t* mask_row = segment.mask.ptr<std::uint8_t>(y - local_box.y);
      for (int x = local_box.x; x < local_box.x + local_box.width; ++x)
      {
        if (label_row[x] != label) continue;
        mask_row[x - local_box.x] = 255;
        const int u = x + roi_px.x;
        if (!std::isnan(depth_row[u])) segment.pixel_indices.push_back(v * image_width_px + u);
      }
    }
    segments.push_back(std::move(segment));
  }
  return segments;
}

void HsvSegmenter::cutAtDepthJumps(cv::Mat& mask, const cv::Mat& depth_m) const
{
  if (params_.depth_jump_m <= 0.0) return;
  const float jump = static_cast<float>(params_.depth_jump_m);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int rows = mask.rows, cols = mask.cols;
  auto differ = [jump](float a, float b) { return std::abs(a - b) > jump; };  // false when either is NaN

  // First depth from (y, x) stepping by (dy, dx) within a few mask pixels:
  // stereo shadows and flying-pixel dropouts leave gaps at depth edges.
  constexpr int kMaxGapPx = 16;  // the shadow of a 0.2 m step at 0.8 m is ~10 px wide
  auto firstValid = [&](int y, int x, int dy, int dx) {
    for (int step = 1; step <= kMaxGapPx; ++step)
    {
      const int yy = y + step * dy, xx = x + step * dx;
      if (yy < 0 || xx < 0 || yy >= rows || xx >= cols || !mask.at<std::uint8_t>(yy, xx)) break;
      const float z = depth_m.at<float>(yy, xx);
      if (!std::isnan(z)) return z;
    }
    return nan;
  };

  // A jump is marked on both sides, so that two cleared pixels separate the
  // plates even under 8-connectivity. Only jumps to another mask pixel
  // count: the outline against the background keeps its pixels. A pixel
  // without depth is cleared when the depths on either side of it differ.
  // Each pair of neighbours with depth is judged once (from its left or
  // upper pixel) and marks both; a pair with a pixel without depth never
  // differs. The marks are applied after the pass, which reads the mask
  // as it was.
  cv::Mat cut = cv::Mat::zeros(rows, cols, CV_8UC1);
  for (int y = 0; y < rows; ++y)
  {
    const std::uint8_t* mask_row = mask.ptr<std::uint8_t>(y);
    const std::uint8_t* mask_down = y + 1 < rows ? mask.ptr<std::uint8_t>(y + 1) : nullptr;
    const float* row = depth_m.ptr<float>(y);
    const float* down = y + 1 < rows ? depth_m.ptr<float>(y + 1) : nullptr;
    std::uint8_t* cut_row = cut.ptr<std::uint8_t>(y);
    std::uint8_t* cut_down = y + 1 < rows ? cut.ptr<std::uint8_t>(y + 1) : nullptr;
    for (int x = 0; x < cols; ++x)
    {
      if (!mask_row[x]) continue;
      const float z = row[x];
      if (std::isnan(z))
      {
        if (differ(firstValid(y, x, 0, -1), firstValid(y, x, 0, 1)) ||
            differ(firstValid(y, x, -1, 0), firstValid(y, x, 1, 0)))
          cut_row[x] = 255;
        continue;
      }
      if (x + 1 < cols && mask_row[x + 1] && differ(z, row[x + 1])) cut_row[x] = cut_row[x + 1] = 255;
      if (mask_down && mask_down[x] && differ(z, down[x])) cut_row[x] = cut_down[x] = 255;
    }
  }
  mask.setTo(0, cut);
}

std::vector<cv::Rect> HsvSegmenter::coarseBoxes(const cv::Mat& coarse_hsv, const HsvRange& range, cv::Size image_size) const
{
  const int factor = params_.coarse_factor;
  const cv::Mat coarse_mask = thresholdHsv(coarse_hsv, range);
  // Half the area a plate of min_area_px would have in the coarse image:
  // generous, the full-resolution pass applies the real threshold.
  const int min_coarse_area = std::max(1, params_.min_area_px / (2 * factor * factor));
  if (cv::countNonZero(coarse_mask) < min_coarse_area) return {};
  cv::Mat labels, stats, centroids;
  const int label_count = cv::connectedComponentsWithStats(coarse_mask, labels, stats, centroids, 8, CV_32S);

  const int pad = 2 * factor + params_.close_kernel_px + params_.open_kernel_px;
  const cv::Rect image(cv::Point(0, 0), image_size);
  std::vector<cv::Rect> boxes;
  for (int label = 1; label < label_count; ++label)
  {
    if (stats.at<int>(label, cv::CC_STAT_AREA) < min_coarse_area) continue;
    const cv::Rect coarse(stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
                          stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    boxes.push_back(cv::Rect(coarse.x * factor - pad, coarse.y * factor - pad, coarse.width * factor + 2 * pad,
                             coarse.height * factor + 2 * pad) &
                    image);
  }
  // Overlapping boxes would find the same full-resolution blob twice.
  for (bool merged = true; merged;)
  {
    merged = false;
    for (std::size_t i = 0; i < boxes.size() && !merged; ++i)
      for (std::size_t j = i + 1; j < boxes.size() && !merged; ++j)
        if ((boxes[i] & boxes[j]).area() > 0)
        {
          boxes[i] |= boxes[j];
          boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(j));
          merged = true;
        }
  }
  return boxes;
}

std::vector<Segment> HsvSegmenter::segment(const RgbdFrame& frame, const BrickCatalogue& catalogue) const
{
  const int factor = params_.coarse_factor;
  const cv::Size image_size = frame.rgb.size();
  // No plate fits an image smaller than the smallest segment, and the coarse
  // search cannot shrink an image thinner than its factor.
  if (image_size.width < factor || image_size.height < factor || image_size.area() < params_.min_area_px) return {};
  cv::Mat coarse_rgb, coarse_hsv;
  if (factor > 1)
    cv::resize(frame.rgb, coarse_rgb, cv::Size(), 1.0 / factor, 1.0 / factor, cv::INTER_NEAREST);
  else
    coarse_rgb = frame.rgb;
  cv::cvtColor(coarse_rgb, coarse_hsv, cv::COLOR_RGB2HSV);

  // A type with no plate colour (a plain box) is for colour-free segmentation.
  std::vector<const BrickType*> coloured;
  for (const BrickType& type : catalogue.types())
    if (type.hasPlateColour()) coloured.push_back(&type);
  // Each type's segments in its own slot, joined in catalogue order.
  std::vector<std::vector<Segment>> found(coloured.size());
  parallelFor(static_cast<int>(coloured.size()), params_.worker_threads, [&](int t) {
    const BrickType& type = *coloured[t];
    std::vector<std::vector<Segment>> in_boxes;
    for (const cv::Rect& box : coarseBoxes(coarse_hsv, *type.plate_hsv, image_size))
    {
      cv::Mat hsv;
      cv::cvtColor(frame.rgb(box), hsv, cv::COLOR_RGB2HSV);
      cv::Mat mask = thresholdHsv(hsv, *type.plate_hsv);
      cleanMask(mask);
      cutAtDepthJumps(mask, frame.depth_m(box));
      in_boxes.push_back(components(mask, frame.depth_m, type.name, box, image_size.width));
    }
    found[t].reserve(totalSize(in_boxes));  // moved in below, never copied
    for (std::vector<Segment>& in_box : in_boxes)
      std::move(in_box.begin(), in_box.end(), std::back_inserter(found[t]));
    std::sort(found[t].begin(), found[t].end(), [](const Segment& a, const Segment& b) { return a.area_px > b.area_px; });
  });
  std::vector<Segment> segments;
  segments.reserve(totalSize(found));
  for (std::vector<Segment>& of_type : found) std::move(of_type.begin(), of_type.end(), std::back_inserter(segments));
  return segments;
}
}  // namespace brick_pose
