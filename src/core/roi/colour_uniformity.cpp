#include "brick_pose/roi/colour_uniformity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/statistics.h"

namespace brick_pose
{
namespace
{
/// Fewer blocks than this say nothing about a face's colour.
constexpr int kMinSamples = 12;

// Per block of a few pixels, cv::countNonZero and cv::mean cost more in
// dispatch than in reading; these read the block directly.
bool allInside(const cv::Mat& mask, const cv::Rect& block)
{
  for (int v = block.y; v < block.y + block.height; ++v)
  {
    const std::uint8_t* row = mask.ptr<std::uint8_t>(v) + block.x;
    for (int u = 0; u < block.width; ++u)
      if (row[u] == 0) return false;
  }
  return true;
}

/// The mean of the block's R, G and B means (the same sums and divisions
/// as averaging cv::mean's three channel means).
double blockGrey(const cv::Mat& rgb, const cv::Rect& block)
{
  long sum[3] = {0, 0, 0};
  for (int v = block.y; v < block.y + block.height; ++v)
  {
    const std::uint8_t* row = rgb.ptr<std::uint8_t>(v) + 3 * block.x;
    for (int u = 0; u < 3 * block.width; u += 3)
    {
      sum[0] += row[u];
      sum[1] += row[u + 1];
      sum[2] += row[u + 2];
    }
  }
  const double scale = 1.0 / block.area();
  return (sum[0] * scale + sum[1] * scale + sum[2] * scale) / 3.0;
}
}  // namespace

cv::Mat withoutRim(const cv::Mat& mask, int rim_px)
{
  cv::Mat inner;
  const int rim = std::max(0, rim_px);
  // Outside the mask's box is outside the face: the border erodes too.
  cv::erode(mask, inner, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * rim + 1, 2 * rim + 1)),
            cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  return inner;
}

ColourUniformity measureColourUniformity(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box,
                                         const ColourUniformityParams& params)
{
  ColourUniformity result;
  if (mask.empty() || box.area() == 0) return result;
  const cv::Mat inner = withoutRim(mask, params.rim_px);
  const int block = std::max(1, params.block_px);
  const int blocks_u = inner.cols / block, blocks_v = inner.rows / block;
  if (blocks_u == 0 || blocks_v == 0) return result;
  const int step = std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(blocks_u) * blocks_v /
                                                                    std::max(1, params.max_samples)))));
  std::vector<double> grey;
  for (int bv = 0; bv < blocks_v; bv += step)
    for (int bu = 0; bu < blocks_u; bu += step)
    {
      const cv::Rect cell(bu * block, bv * block, block, block);
      const cv::Rect in_frame = cell + box.tl();
      // Whole blocks inside the face and the image only.
      if ((in_frame & cv::Rect(0, 0, frame.width_px(), frame.height_px())) != in_frame) continue;
      if (!allInside(inner, cell)) continue;
      grey.push_back(blockGrey(frame.rgb, in_frame));
    }
  result.samples = static_cast<int>(grey.size());
  if (result.samples < kMinSamples) return result;
  result.median_grey = percentile(grey, 0.5);
  std::vector<double> deviation(grey.size());
  for (std::size_t k = 0; k < grey.size(); ++k) deviation[k] = std::abs(grey[k] - result.median_grey);
  result.sigma_grey = 1.4826 * percentile(deviation, 0.5);
  const double limit = std::max(params.min_contrast, params.outlier_sigmas * result.sigma_grey);
  const auto outliers = std::count_if(deviation.begin(), deviation.end(), [&](double d) { return d > limit; });
  result.outlier_fraction = static_cast<double>(outliers) / result.samples;
  result.uniform = result.sigma_grey <= params.max_sigma_grey && result.outlier_fraction <= params.max_outlier_fraction;
  return result;
}
namespace
{
/// The mean colour (B, G, R) of the pixels of `mask` placed at `box`;
/// nothing when none is in the image.
std::optional<cv::Vec3d> meanColour(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box)
{
  const cv::Rect inside = box & cv::Rect(0, 0, frame.width_px(), frame.height_px());
  if (inside.area() == 0 || mask.empty()) return std::nullopt;
  const cv::Mat inside_mask = mask(cv::Rect(inside.tl() - box.tl(), inside.size()));
  if (cv::countNonZero(inside_mask) == 0) return std::nullopt;
  const cv::Scalar bgr = cv::mean(frame.rgb(inside), inside_mask);
  return cv::Vec3d(bgr[0], bgr[1], bgr[2]);
}
}  // namespace

double meanGreyLevel(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box)
{
  const std::optional<cv::Vec3d> bgr = meanColour(frame, mask, box);
  return bgr ? ((*bgr)[0] + (*bgr)[1] + (*bgr)[2]) / 3.0 : 0.0;
}

double faceGreyLevel(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box)
{
  const std::optional<cv::Vec3d> bgr = meanColour(frame, mask, box);
  if (!bgr) return 0.0;
  return FaceGrey::ofColour(*bgr)(*bgr);
}

FaceGrey faceGreyOf(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box)
{
  const std::optional<cv::Vec3d> bgr = meanColour(frame, mask, box);
  return bgr ? FaceGrey::ofColour(*bgr) : FaceGrey();
}
}  // namespace brick_pose
