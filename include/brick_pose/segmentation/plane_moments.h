#pragma once
// Sufficient statistics of a point set for plane fitting: the count, the sum
// and the sum of outer products. Two sets merge by adding their moments, so
// the plane of a union of pixel blocks costs O(1) whatever its size (the
// idea that makes agglomerative plane clustering on organised clouds run in
// real time, Feng et al. ICRA 2014).

#include <Eigen/Core>

namespace brick_pose
{
struct PlaneMoments
{
  double count = 0.0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  /// Upper triangle of sum(p p^T): xx, xy, xz, yy, yz, zz.
  double xx = 0.0, xy = 0.0, xz = 0.0, yy = 0.0, yz = 0.0, zz = 0.0;
  /// Sum of z^4: with a noise sigma growing as z^2, the set's expected
  /// residual variance is coefficient^2 * z4 / count.
  double z4 = 0.0;

  void add(double x, double y, double z)
  {
    count += 1.0;
    sum.x() += x;
    sum.y() += y;
    sum.z() += z;
    xx += x * x;
    xy += x * y;
    xz += x * z;
    yy += y * y;
    yz += y * z;
    zz += z * z;
    z4 += (z * z) * (z * z);
  }

  PlaneMoments& operator+=(const PlaneMoments& other);

  Eigen::Vector3d mean() const { return sum / count; }
  /// Population covariance (divided by count); needs count > 0.
  Eigen::Matrix3d covariance() const;
};

inline PlaneMoments operator+(PlaneMoments a, const PlaneMoments& b) { return a += b; }

/// Least-squares plane of a set of moments.
struct MomentPlane
{
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< Unit, toward the camera (normal . centroid < 0).
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  double count = 0.0;
  /// Mean squared distance of the points to the plane (smallest eigenvalue).
  double mse_m2 = 0.0;
  /// Variance of the points along the plane's narrower in-plane axis (middle
  /// eigenvalue): with the noise it sets how well the normal is known.
  double narrow_variance_m2 = 0.0;
  bool valid = false;  ///< False for fewer than 3 points or a degenerate (collinear) set.

  double signedDistance(const Eigen::Vector3d& point_m) const { return normal.dot(point_m - centroid_m); }
  /// Mean squared distance of the points summarised by `moments` to this plane.
  double meanSquaredDistance(const PlaneMoments& moments) const;
};

MomentPlane fitMomentPlane(const PlaneMoments& moments);

/// The same fit started from a normal close to the answer (the plane of a
/// node before a merge): two steps of inverse iteration on the covariance
/// instead of the closed-form eigen decomposition, which costs several
/// times more. Falls back to fitMomentPlane() when the guess does not
/// converge (no clearly smallest eigenvalue).
MomentPlane refitMomentPlane(const PlaneMoments& moments, const Eigen::Vector3d& normal_guess);
}  // namespace brick_pose
