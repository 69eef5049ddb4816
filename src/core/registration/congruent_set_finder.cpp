#include "brick_pose/registration/congruent_set_finder.h"

#include <algorithm>
#include <cmath>

#include "brick_pose/registration/point_grid.h"

namespace brick_pose
{
namespace registration
{
namespace
{
double angleBetween(const Eigen::Vector3d& u, const Eigen::Vector3d& v)
{
  return std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0));
}
}  // namespace

CongruentSetFinder::CongruentSetFinder(const PointSet& target, const ShellPairIndex& index)
  : target_(target), index_(index)
{
  // Every base tests its shell pairs' normals: normalised once here, not per pair.
  unit_normals_.reserve(target.normals.size());
  for (const Eigen::Vector3d& normal : target.normals)
    unit_normals_.push_back(normal.normalized());
}

namespace
{
/// The cosines c with |acos(c) - angle| <= tolerance: [cos(angle + tol), cos(angle - tol)],
/// the ends clamped to [0, pi]. Comparing cosines spares an acos per pair.
struct CosineRange
{
  double min = -1.0;
  double max = 1.0;
  CosineRange(double angle_rad, double tolerance_rad)
    : min(std::cos(std::min(M_PI, angle_rad + tolerance_rad))), max(std::cos(std::max(0.0, angle_rad - tolerance_rad)))
  {
  }
  bool contains(double cosine) const { return cosine >= min && cosine <= max; }
};
}  // namespace

CongruentSetFinder::PairNormalRanges::PairNormalRanges(const Eigen::Vector3d& base_p, const Eigen::Vector3d& base_q,
                                                      const Eigen::Vector3d& base_np, const Eigen::Vector3d& base_nq,
                                                      double tolerance_rad)
{
  const Eigen::Vector3d base_segment = base_q - base_p;
  const double angles[3] = {angleBetween(base_np, base_nq), angleBetween(base_np, base_segment),
                            angleBetween(base_nq, base_segment)};
  for (int k = 0; k < 3; ++k)
  {
    min_cos[k] = std::cos(std::min(M_PI, angles[k] + tolerance_rad));
    max_cos[k] = std::cos(std::max(0.0, angles[k] - tolerance_rad));
  }
}

// Rigid motions keep the angles between the two normals and between each
// normal and the segment joining the points; the angles are compared through
// their cosines (|acos(c) - a| <= t  <=>  cos(a + t) <= c <= cos(a - t)).
// The reverse pair (q, p) has the segment negated exactly, so its cosines are
// the forward ones with the last two swapped and negated: one set of dot
// products decides both orders.
CongruentSetFinder::PairAgreement CongruentSetFinder::normalsAgree(int p, int q, const PairNormalRanges& ranges) const
{
  const Eigen::Vector3d& np = unit_normals_[p];
  const Eigen::Vector3d& nq = unit_normals_[q];
  const Eigen::Vector3d segment = (target_.points[q] - target_.points[p]).normalized();
  // Round-off puts the dot product of equal unit normals just above 1.
  const double between = std::clamp(np.dot(nq), -1.0, 1.0);
  const double p_side = std::clamp(np.dot(segment), -1.0, 1.0);
  const double q_side = std::clamp(nq.dot(segment), -1.0, 1.0);
  PairAgreement agreement;
  if (!ranges.inRange(0, between))
    return agreement;
  agreement.forward = ranges.inRange(1, p_side) && ranges.inRange(2, q_side);
  agreement.reverse = ranges.inRange(1, -q_side) && ranges.inRange(2, -p_side);
  return agreement;
}

std::vector<std::pair<int, int>> CongruentSetFinder::orderedPairs(double radius_m, const Eigen::Vector3d& base_p,
                                                                  const Eigen::Vector3d& base_q,
                                                                  const Eigen::Vector3d& base_np,
                                                                  const Eigen::Vector3d& base_nq,
                                                                  const CongruenceTolerances& tolerances) const
{
  const bool use_normals = target_.hasNormals() && base_np.squaredNorm() > 0.0 && base_nq.squaredNorm() > 0.0;
  const PairNormalRanges forward(base_p, base_q, base_np, base_nq, tolerances.normal_rad);
  std::vector<std::pair<int, int>> ordered;
  for (const auto& [i, j] : index_.pairsInShell(radius_m, tolerances.distance_m))
  {
    // Both orders: the crossing point divides p-q in the ratio t : (1 - t).
    const PairAgreement agreement = use_normals ? normalsAgree(i, j, forward) : PairAgreement{true, true};
    if (agreement.forward)
      ordered.emplace_back(i, j);
    if (agreement.reverse)
      ordered.emplace_back(j, i);
  }
  return ordered;
}

long CongruentSetFinder::find(const CoplanarBase& base, const CongruenceTolerances& tolerances,
                              const std::function<bool(const CongruentSet&)>& on_set) const
{
  const std::vector<Eigen::Vector3d>& q = target_.points;
  const auto first = orderedPairs(base.r1_m(), base.points[0], base.points[1], base.normals[0], base.normals[1],
                                  tolerances);
  if (first.empty())
    return 0;
  const auto second = orderedPairs(base.r2_m(), base.points[2], base.points[3], base.normals[2], base.normals[3],
                                   tolerances);
  if (second.empty())
    return 0;

  std::vector<Eigen::Vector3d> crossings(first.size());
  std::vector<Eigen::Vector3d> first_directions(first.size());
  for (std::size_t k = 0; k < first.size(); ++k)
  {
    const Eigen::Vector3d& a = q[first[k].first];
    const Eigen::Vector3d& b = q[first[k].second];
    crossings[k] = a + base.t1 * (b - a);
    first_directions[k] = (b - a).normalized();
  }
  const PointGrid crossing_grid(crossings, tolerances.distance_m);
  const double base_angle_rad = base.segmentAngle_rad();

  long reported = 0;
  bool keep_going = true;
  for (std::size_t k = 0; k < second.size() && keep_going; ++k)
  {
    const auto [c, d] = second[k];
    const Eigen::Vector3d crossing = q[c] + base.t2 * (q[d] - q[c]);
    const Eigen::Vector3d direction = (q[d] - q[c]).normalized();
    crossing_grid.forEachWithin(crossing, tolerances.distance_m, [&](int m) {
      if (!keep_going)
        return;
      const auto [a, b] = first[m];
      if (a == c || a == d || b == c || b == d)
        return;
      const double angle_rad = std::acos(std::clamp(first_directions[m].dot(direction), -1.0, 1.0));
      if (std::abs(angle_rad - base_angle_rad) > tolerances.angle_rad)
        return;
      ++reported;
      keep_going = on_set({{a, b, c, d}});
    });
  }
  return reported;
}
}  // namespace registration
}  // namespace brick_pose
