#include "brick_pose/registration/box_placement.h"

#include <algorithm>

namespace brick_pose
{
namespace registration
{
namespace
{
/// The `trim`-th smallest and largest of `values` (selected, not sorted);
/// needs more than 2 * trim + 1 values.
std::pair<double, double> trimmedExtremes(std::vector<double> values, int trim)
{
  const auto low = values.begin() + trim;
  std::nth_element(values.begin(), low, values.end());
  const double lower = *low;
  const auto high = values.end() - 1 - trim;
  std::nth_element(low, high, values.end());
  return {lower, *high};
}

/// The shift along one box axis (box coordinates) that puts the scan's
/// extent [lower, upper] where the camera, at `camera` on that axis, sees
/// the box of half extent `half`. The camera is judged against the scan, not
/// the box: the box is still where the turn left it.
double shiftAlongAxis(double lower, double upper, double camera, double half)
{
  if (camera > upper)
    return upper - half;
  if (camera < lower)
    return lower + half;
  return 0.5 * (lower + upper);
}
}  // namespace

Eigen::Isometry3d anchoredToScanExtent(const Eigen::Isometry3d& pose, const ModelSymmetries& symmetries,
                                       const std::vector<Eigen::Vector3d>& scan_points,
                                       const Eigen::Vector3d& viewpoint_m, int trim_points)
{
  trim_points = std::max(0, trim_points);
  if (!symmetries.box_like || scan_points.size() < static_cast<std::size_t>(2 * trim_points + 2))
    return pose;
  const Eigen::Isometry3d target_to_model = pose.inverse();
  const Eigen::Matrix3d to_box = symmetries.axes.transpose();
  const Eigen::Vector3d camera = to_box * (target_to_model * viewpoint_m - symmetries.centre_m);
  std::vector<double> along[3];
  for (const Eigen::Vector3d& point : scan_points)
  {
    const Eigen::Vector3d local = to_box * (target_to_model * point - symmetries.centre_m);
    for (int axis = 0; axis < 3; ++axis)
      along[axis].push_back(local(axis));
  }
  Eigen::Vector3d shift_box;
  for (int axis = 0; axis < 3; ++axis)
  {
    const std::pair<double, double> extremes = trimmedExtremes(std::move(along[axis]), trim_points);
    shift_box(axis) =
        shiftAlongAxis(extremes.first, extremes.second, camera(axis), symmetries.half_extents_m(axis));
  }
  Eigen::Isometry3d moved = pose;
  moved.translation() += pose.linear() * (symmetries.axes * shift_box);
  return moved;
}
}  // namespace registration
}  // namespace brick_pose
