#pragma once
// Finds the 4-point sets of the target congruent to a base (Super 4PCS sec. 4):
// pairs at the two diagonal lengths come from the ShellPairIndex, are filtered
// by normals, and are matched through the crossing points e = p + t (q - p)
// hashed in a grid, with the angle between the two diagonals checked.

#include <array>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/coplanar_base.h"
#include "brick_pose/registration/point_set.h"
#include "brick_pose/registration/shell_pair_index.h"

namespace brick_pose
{
namespace registration
{
struct CongruenceTolerances
{
  double distance_m = 0.0;  ///< pair lengths and crossing points
  double angle_rad = 0.0;  ///< between the two diagonals
  double normal_rad = 0.0;  ///< normal angle checks (only with normals)
};

/// Target indices matching base points a, b, c, d in that order.
using CongruentSet = std::array<int, 4>;

/// With normals, a candidate must also turn each base normal onto the normal
/// of its set point, `set_normal(k)`, within `max_angle_rad`: the pair filters
/// only compare normals with each other, which cannot tell a flat face from the
/// same face seen from behind. The caller decides whether its set normals need
/// normalising, so unit normals are used as they are.
template <typename SetNormal>
bool baseNormalsMapped(const Eigen::Isometry3d& transform, const CoplanarBase& base, SetNormal set_normal,
                       double max_angle_rad)
{
  const double min_cos = std::cos(max_angle_rad);
  for (int k = 0; k < 4; ++k)
    if ((transform.linear() * base.normals[k]).dot(set_normal(k)) < min_cos) return false;
  return true;
}

class CongruentSetFinder
{
public:
  /// `target` and `index` (built on target.points) must outlive the finder.
  CongruentSetFinder(const PointSet& target, const ShellPairIndex& index);

  /// Calls on_set for every congruent set found; on_set returns false to stop
  /// the enumeration. Returns the number of sets reported.
  long find(const CoplanarBase& base, const CongruenceTolerances& tolerances,
            const std::function<bool(const CongruentSet&)>& on_set) const;

  /// Ordered target pairs (p, q) that may play the base pair (base_p, base_q):
  /// length r +- tolerance and, with normals, the same normal angles.
  std::vector<std::pair<int, int>> orderedPairs(double radius_m, const Eigen::Vector3d& base_p,
                                                const Eigen::Vector3d& base_q, const Eigen::Vector3d& base_np,
                                                const Eigen::Vector3d& base_nq,
                                                const CongruenceTolerances& tolerances) const;

private:
  /// Cosine bounds of the three angles a target pair must match (between the
  /// normals, and between each normal and the segment).
  struct PairNormalRanges
  {
    PairNormalRanges(const Eigen::Vector3d& base_p, const Eigen::Vector3d& base_q, const Eigen::Vector3d& base_np,
                     const Eigen::Vector3d& base_nq, double tolerance_rad);
    double min_cos[3];
    double max_cos[3];
    bool inRange(int k, double cosine) const { return cosine >= min_cos[k] && cosine <= max_cos[k]; }
  };
  /// Whether the pair's normals agree with the base pair's in the order
  /// (p, q) and in the order (q, p).
  struct PairAgreement
  {
    bool forward = false;
    bool reverse = false;
  };
  PairAgreement normalsAgree(int p, int q, const PairNormalRanges& ranges) const;

  const PointSet& target_;
  const ShellPairIndex& index_;
  std::vector<Eigen::Vector3d> unit_normals_;
};
}  // namespace registration
}  // namespace brick_pose
