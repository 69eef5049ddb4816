#pragma once
// The 4-point coplanar base of 4PCS and its affine invariants.

#include <array>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
/// Four (almost) coplanar points a, b, c, d whose "diagonals" a-b and c-d
/// cross at e = a + t1 (b - a) = c + t2 (d - c). The ratios t1, t2 are kept by
/// any affine map, hence by the rigid motion to a congruent target set.
struct CoplanarBase
{
  std::array<int, 4> indices{{-1, -1, -1, -1}};
  std::array<Eigen::Vector3d, 4> points;
  std::array<Eigen::Vector3d, 4> normals;  ///< zero when the cloud has none
  double t1 = 0.0;
  double t2 = 0.0;
  double r1_m() const { return (points[1] - points[0]).norm(); }
  double r2_m() const { return (points[3] - points[2]).norm(); }
  /// Angle between the directions b - a and d - c, in [0, pi].
  double segmentAngle_rad() const;
};

struct BaseSelectionLimits
{
  double max_diameter_m = 0.0;  ///< no two base points further apart (overlap bound)
  double coplanar_tolerance_m = 0.0;  ///< distance of d to the plane of a, b, c
  /// Crossing ratios kept inside [min, 1 - min] so e is well inside both
  /// diagonals (a crossing at an end point gives no constraint).
  double min_crossing_ratio = 0.15;
  int attempts = 24;  ///< random triples tried before giving up
  /// With normals: some two of the four base normals must differ by at least
  /// this (0 = no requirement). A base spanning two faces of a cuboid view
  /// fits far fewer places of the model than one on a single flat face, which
  /// fits anywhere on any face as large.
  double min_normal_spread_rad = 0.0;
};

/// Draws a wide base from `cloud`: a and b near max_diameter_m apart, c far
/// from the line a-b, d on the other side so that the diagonals cross.
/// Returns nothing when no suitable base was found within the attempts.
std::optional<CoplanarBase> drawCoplanarBase(const PointSet& cloud, const BaseSelectionLimits& limits,
                                             std::mt19937_64& rng);

/// Closest-point parameters of the lines a-b and c-d (t1 on a-b, t2 on c-d);
/// false when the lines are parallel.
bool crossingRatios(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d, double& t1, double& t2);
}  // namespace registration
}  // namespace brick_pose
