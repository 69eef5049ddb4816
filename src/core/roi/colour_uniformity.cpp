#include "brick_pose/roi/colour_uniformity.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/statistics.h"

namespace brick_pose
{
namespace
{
/// Fewer pixels than this say nothing about a face's colour.
constexpr int kMinSamples = 50;
}  // namespace

ColourUniformity measureColourUniformity(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box,
                                         const ColourUniformityParams& params)
{
  ColourUniformity result;
  if (mask.empty() || box.area() == 0) return result;
  cv::Mat inner;
  const int rim = std::max(0, params.rim_px);
  // Outside the mask's box is outside the face: the border erodes too.
  cv::erode(mask, inner, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * rim + 1, 2 * rim + 1)),
            cv::Point(-1, -1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  const int inside = cv::countNonZero(inner);
  if (inside < kMinSamples) return result;
  const int step = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(inside) / std::max(1, params.max_samples))));
  std::vector<double> grey;
  grey.reserve(static_cast<std::size_t>(inside / (step * step) + 1));
  for (int v = 0; v < inner.rows; v += step)
  {
    const unsigned char* row = inner.ptr<unsigned char>(v);
    const int frame_v = v + box.y;
    if (frame_v < 0 || frame_v >= frame.height_px()) continue;
    const cv::Vec3b* rgb = frame.rgb.ptr<cv::Vec3b>(frame_v);
    for (int u = 0; u < inner.cols; u += step)
    {
      const int frame_u = u + box.x;
      if (!row[u] || frame_u < 0 || frame_u >= frame.width_px()) continue;
      grey.push_back((static_cast<double>(rgb[frame_u][0]) + rgb[frame_u][1] + rgb[frame_u][2]) / 3.0);
    }
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
}  // namespace brick_pose
