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

/// Calls `visit(disparity_px)` for every pixel of the square window of
/// `radius` around (u, v) that lies inside the image; fattening and smoothing
/// both look at exactly this neighbourhood.
template <typename Visit>
void forEachInWindow(const cv::Mat& disparity, int u, int v, int radius, Visit visit)
{
  for (int dv = -radius; dv <= radius; ++dv)
  {
    const int y = v + dv;
    if (y < 0 || y >= disparity.rows) continue;
    const float* row = disparity.ptr<float>(y);
    for (int du = -radius; du <= radius; ++du)
    {
      const int x = u + du;
      if (x < 0 || x >= disparity.cols) continue;
      visit(row[x]);
    }
  }
}

/// A copy of `disparity` whose active pixels take `filtered(u, v, centre)`;
/// outside the active mask the filters are no-ops, so they are skipped.
template <typename Filter>
cv::Mat filterActive(const cv::Mat& disparity, const cv::Mat& active, int radius, Filter filtered)
{
  cv::Mat out = disparity.clone();
  if (radius <= 0) return out;
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u)
      if (active.at<unsigned char>(v, u)) out.at<float>(v, u) = filtered(u, v, disparity.at<float>(v, u));
  return out;
}

/// The nearer surface wins a pixel within `radius` of it when it is clearly
/// nearer (more than the blend threshold).
cv::Mat fatten(const cv::Mat& disparity, const cv::Mat& active, int radius)
{
  const float blend = static_cast<float>(kBlendDisparityPx);
  return filterActive(disparity, active, radius, [&](int u, int v, float centre) {
    float best = centre;
    forEachInWindow(disparity, u, v, radius, [&](float neighbour) {
      if (neighbour > centre + blend && neighbour > best) best = neighbour;
    });
    return best;
  });
}

/// Mean disparity over the window of the pixels matched together with the
/// centre (within the blend threshold of it).
cv::Mat smooth(const cv::Mat& disparity, const cv::Mat& active, int radius)
{
  const float blend = static_cast<float>(kBlendDisparityPx);
  return filterActive(disparity, active, radius, [&](int u, int v, float centre) {
    // No depth stays no depth (the copy keeps the centre).
    if (centre <= 0.0f) return centre;
    double sum = 0.0;
    int count = 0;
    forEachInWindow(disparity, u, v, radius, [&](float neighbour) {
      if (std::abs(neighbour - centre) <= blend)
      {
        sum += neighbour;
        ++count;
      }
    });
    return static_cast<float>(sum / count);
  });
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
