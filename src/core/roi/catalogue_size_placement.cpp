#include "brick_pose/roi/catalogue_size_placement.h"

#include <algorithm>

namespace brick_pose
{
bool depthBoundsEdge(EdgeKind kind)
{
  return kind == EdgeKind::kStepDown || kind == EdgeKind::kCrease || kind == EdgeKind::kDropBesideWall;
}

std::array<Eigen::Vector3d, 4> cornersTrimmedToSize(const std::array<Eigen::Vector3d, 4>& corners_m,
                                                    const EdgeKinds& kinds, double length_m, double width_m,
                                                    double max_trim_m)
{
  const Eigen::Vector3d centre = 0.25 * (corners_m[0] + corners_m[1] + corners_m[2] + corners_m[3]);
  std::array<Eigen::Vector3d, 4> middle, inward;
  for (int k = 0; k < 4; ++k)
  {
    const Eigen::Vector3d& a = corners_m[k];
    const Eigen::Vector3d& b = corners_m[(k + 1) % 4];
    middle[k] = 0.5 * (a + b);
    const Eigen::Vector3d along = (b - a).normalized();
    const Eigen::Vector3d to_centre = centre - middle[k];
    inward[k] = (to_centre - to_centre.dot(along) * along).normalized();
  }
  // Edges 0 and 2 lie a width apart, edges 1 and 3 a length.
  std::array<double, 4> trim_m{};
  for (int first = 0; first < 2; ++first)
  {
    const int second = first + 2;
    const double extent_m = (middle[second] - middle[first]).dot(inward[first]);
    const double excess_m = std::min(max_trim_m, extent_m - (first == 0 ? width_m : length_m));
    if (!(excess_m > 0.0)) continue;
    const bool first_by_depth = depthBoundsEdge(kinds[first]), second_by_depth = depthBoundsEdge(kinds[second]);
    const double first_share = first_by_depth == second_by_depth ? 0.5 : first_by_depth ? 1.0 : 0.0;
    trim_m[first] = first_share * excess_m;
    trim_m[second] = (1.0 - first_share) * excess_m;
  }
  std::array<Eigen::Vector3d, 4> trimmed;
  for (int k = 0; k < 4; ++k)
  {
    const int before = (k + 3) % 4;  // corner k joins edges k - 1 and k
    trimmed[k] = corners_m[k] + trim_m[k] * inward[k] + trim_m[before] * inward[before];
  }
  return trimmed;
}
}  // namespace brick_pose
