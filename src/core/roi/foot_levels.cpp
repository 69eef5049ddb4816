#include "brick_pose/roi/foot_levels.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "brick_pose/roi/raised_layer.h"

namespace brick_pose
{
namespace
{
/// The point pixel (u, v) sees; false off the image or without depth.
bool pointAt(const RgbdFrame& frame, int u, int v, Eigen::Vector3d& point_m)
{
  if (u < 0 || v < 0 || u >= frame.width_px() || v >= frame.height_px()) return false;
  const float z = frame.depthAt(u, v);
  if (!(z > 0.0f)) return false;
  point_m = frame.camera.backProject(u, v, z);
  return true;
}

/// Whether the surface at `point_m` (pixel (u, v)) lies level: its normal,
/// from the depth `params.normal_baseline_px` to either side along each
/// image axis, within max_level_tilt_deg (cosine `min_cos_tilt`) of `up`,
/// and the point midway between each pair within max_bend_m of it. A pixel
/// across a depth jump (a mix of a near and a far surface, at any height
/// between them) has no such neighbourhood. Unknown (no depth around, the
/// image border) is not level.
bool levelAt(const RgbdFrame& frame, int u, int v, const Eigen::Vector3d& point_m, const Eigen::Vector3d& up,
             double min_cos_tilt, const FootLevelParams& params)
{
  const int baseline_px = params.normal_baseline_px;
  Eigen::Vector3d left, right, above, below;
  if (!pointAt(frame, u - baseline_px, v, left) || !pointAt(frame, u + baseline_px, v, right) ||
      !pointAt(frame, u, v - baseline_px, above) || !pointAt(frame, u, v + baseline_px, below))
    return false;
  if ((0.5 * (left + right) - point_m).norm() > params.max_bend_m ||
      (0.5 * (above + below) - point_m).norm() > params.max_bend_m)
    return false;
  const Eigen::Vector3d normal = (right - left).cross(below - above);
  const double norm = normal.norm();
  return norm > 0.0 && std::abs(normal.dot(up)) >= min_cos_tilt * norm;
}

/// The heights above the support of the ring's pixels lower than the face
/// that lie on a level surface.
std::vector<double> lowerRingHeights(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box_px,
                                     const PlaneFit& plane, const UpDirection& support, const FootLevelParams& params)
{
  std::vector<double> heights_m;
  const double min_cos_tilt = std::cos(params.max_level_tilt_deg * M_PI / 180.0);
  const OutlineRing ring = outlineRing(frame, mask, box_px, params.inner_px, params.outer_px);
  for (int y = 0; y < ring.ring.rows; ++y)
  {
    const std::uint8_t* on_ring = ring.ring.ptr<std::uint8_t>(y);
    for (int x = 0; x < ring.ring.cols; ++x)
    {
      if (!on_ring[x]) continue;
      const int u = ring.box_px.x + x, v = ring.box_px.y + y;
      Eigen::Vector3d point;
      if (!pointAt(frame, u, v, point)) continue;
      // A side face below the face's edge (its own, seen obliquely, or a
      // lower neighbour's) has pixels at every height down it, densest just
      // where the ring crosses it: only level surfaces are places to stand.
      if (plane.signedDistance(point) < -params.below_face_m &&
          levelAt(frame, u, v, point, support.support_normal, min_cos_tilt, params))
      {
        heights_m.push_back(support.heightAboveSupport(point));
      }
    }
  }
  return heights_m;
}
}  // namespace

std::vector<double> levelsAroundFoot(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box_px,
                                     const PlaneFit& plane, const UpDirection& support, double tolerance_m,
                                     const FootLevelParams& params)
{
  std::vector<double> levels_m;
  if (!support.has_support_plane || mask.empty() || !plane.valid || params.outer_px <= params.inner_px)
    return levels_m;
  std::vector<double> heights_m = lowerRingHeights(frame, mask, box_px, plane, support, params);
  const std::size_t needed =
      std::max<std::size_t>(params.min_pixels, static_cast<std::size_t>(std::ceil(params.min_share * heights_m.size())));
  std::sort(heights_m.begin(), heights_m.end());
  // The densest window of 2 x tolerance, again and again, each taking its
  // pixels: the ring's floor first, then a deck or a lower box.
  while (heights_m.size() >= needed)
  {
    std::size_t best_first = 0, best_count = 0;
    for (std::size_t first = 0, last = 0; first < heights_m.size(); ++first)
    {
      while (last < heights_m.size() && heights_m[last] <= heights_m[first] + 2.0 * tolerance_m) ++last;
      if (last - first > best_count)
      {
        best_count = last - first;
        best_first = first;
      }
    }
    if (best_count < needed) break;
    const double level_m = heights_m[best_first + best_count / 2];
    if (std::abs(level_m) > tolerance_m) levels_m.push_back(level_m);
    heights_m.erase(heights_m.begin() + static_cast<std::ptrdiff_t>(best_first),
                    heights_m.begin() + static_cast<std::ptrdiff_t>(best_first + best_count));
  }
  return levels_m;
}
}  // namespace brick_pose
