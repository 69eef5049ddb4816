#include "brick_pose/sim/stereo_matching.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/imgproc.hpp>

namespace brick_pose
{
namespace sim
{
namespace
{
/// Disparity in pixels, 0 where there is no depth (infinitely far).
cv::Mat disparityOf(const cv::Mat& depth_m, double focal_baseline)
{
  cv::Mat disparity(depth_m.size(), CV_32FC1);
  for (int v = 0; v < depth_m.rows; ++v)
  {
    const float* depth = depth_m.ptr<float>(v);
    float* out = disparity.ptr<float>(v);
    for (int u = 0; u < depth_m.cols; ++u)
      out[u] = std::isnan(depth[u]) || depth[u] <= 0.0f ? 0.0f : static_cast<float>(focal_baseline / depth[u]);
  }
  return disparity;
}

/// The nearer surface wins a pixel within `radius` of it when it is clearly
/// nearer (more than the blend threshold).
cv::Mat fatten(const cv::Mat& disparity, const cv::Mat& active, int radius)
{
  cv::Mat out = disparity.clone();
  if (radius <= 0) return out;
  const float blend = static_cast<float>(kBlendDisparityPx);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u)
    {
      if (!active.at<unsigned char>(v, u)) continue;
      const float centre = disparity.at<float>(v, u);
      float best = centre;
      for (int dv = -radius; dv <= radius; ++dv)
      {
        const int y = v + dv;
        if (y < 0 || y >= disparity.rows) continue;
        const float* row = disparity.ptr<float>(y);
        for (int du = -radius; du <= radius; ++du)
        {
          const int x = u + du;
          if (x < 0 || x >= disparity.cols) continue;
          if (row[x] > centre + blend && row[x] > best) best = row[x];
        }
      }
      out.at<float>(v, u) = best;
    }
  return out;
}

/// Mean disparity over the window of the pixels matched together with the
/// centre (within the blend threshold of it).
cv::Mat smooth(const cv::Mat& disparity, const cv::Mat& active, int radius)
{
  cv::Mat out = disparity.clone();
  if (radius <= 0) return out;
  const float blend = static_cast<float>(kBlendDisparityPx);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u)
    {
      if (!active.at<unsigned char>(v, u)) continue;
      const float centre = disparity.at<float>(v, u);
      if (centre <= 0.0f) continue;
      double sum = 0.0;
      int count = 0;
      for (int dv = -radius; dv <= radius; ++dv)
      {
        const int y = v + dv;
        if (y < 0 || y >= disparity.rows) continue;
        const float* row = disparity.ptr<float>(y);
        for (int du = -radius; du <= radius; ++du)
        {
          const int x = u + du;
          if (x < 0 || x >= disparity.cols) continue;
          if (std::abs(row[x] - centre) <= blend)
          {
            sum += row[x];
            ++count;
          }
        }
      }
      out.at<float>(v, u) = static_cast<float>(sum / count);
    }
  return out;
}
}  // namespace

cv::Mat stereoMatchedDepth(const cv::Mat& depth_m, const cv::Mat& boundaries, const StereoWindow& window)
{
  const int smooth_radius = std::max(0, window.window_px / 2);
  const int fattening = std::max(0, window.fattening_px);
  if (smooth_radius == 0 && fattening == 0) return depth_m.clone();

  // Fattening changes pixels within `fattening` of a boundary, smoothing
  // those within its radius of a changed one; elsewhere both are exact no-ops.
  cv::Mat active;
  const int reach = smooth_radius + fattening;
  cv::dilate(boundaries != 0, active, cv::getStructuringElement(cv::MORPH_RECT, {2 * reach + 1, 2 * reach + 1}));

  const cv::Mat disparity = disparityOf(depth_m, window.focal_baseline_px_m);
  const cv::Mat matched = smooth(fatten(disparity, active, fattening), active, smooth_radius);

  cv::Mat out = depth_m.clone();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int v = 0; v < out.rows; ++v)
    for (int u = 0; u < out.cols; ++u)
    {
      if (!active.at<unsigned char>(v, u)) continue;
      const float d = matched.at<float>(v, u);
      out.at<float>(v, u) = d > 0.0f ? static_cast<float>(window.focal_baseline_px_m / d) : nan;
    }
  return out;
}
}  // namespace sim
}  // namespace brick_pose
