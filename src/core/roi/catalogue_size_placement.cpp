#include "brick_pose/roi/catalogue_size_placement.h"

#include <algorithm>
#include <cmath>

namespace brick_pose
{
bool depthBoundsEdge(EdgeKind kind)
{
  return kind == EdgeKind::kStepDown || kind == EdgeKind::kCrease || kind == EdgeKind::kDropBesideWall;
}

namespace
{
/// The share of an axis's excess the first of its two depth-bounded ends
/// takes, from where colour shows each end (NaN: not seen). Two ends seen
/// must agree with the excess within `agreement_m`; one end seen is taken
/// up to the excess. Otherwise (and with neither seen) half each.
double firstEndsShare(double first_inset_m, double second_inset_m, double excess_m, double agreement_m)
{
  const bool first_seen = std::isfinite(first_inset_m), second_seen = std::isfinite(second_inset_m);
  if (first_seen && second_seen)
  {
    const double first = std::max(0.0, first_inset_m), both = first + std::max(0.0, second_inset_m);
    return both > 0.0 && std::abs(both - excess_m) <= agreement_m ? first / both : 0.5;
  }
  if (first_seen && first_inset_m <= excess_m) return std::max(0.0, first_inset_m) / excess_m;
  if (second_seen && second_inset_m <= excess_m) return 1.0 - std::max(0.0, second_inset_m) / excess_m;
  return 0.5;
}
}  // namespace

std::array<Eigen::Vector3d, 4> cornersTrimmedToSize(const std::array<Eigen::Vector3d, 4>& corners_m,
                                                    const EdgeKinds& kinds, double length_m, double width_m,
                                                    double max_trim_m, const std::array<double, 4>& colour_inset_m,
                                                    double colour_agreement_m)
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
    const double first_share =
        first_by_depth && second_by_depth
            ? firstEndsShare(colour_inset_m[first], colour_inset_m[second], excess_m, colour_agreement_m)
            : first_by_depth == second_by_depth ? 0.5 : first_by_depth ? 1.0 : 0.0;
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
