#include "brick_pose/segmentation/plane_moments.h"

#include <cmath>

#include <Eigen/Eigenvalues>

namespace brick_pose
{
PlaneMoments& PlaneMoments::operator+=(const PlaneMoments& other)
{
  count += other.count;
  sum += other.sum;
  xx += other.xx;
  xy += other.xy;
  xz += other.xz;
  yy += other.yy;
  yz += other.yz;
  zz += other.zz;
  z4 += other.z4;
  return *this;
}

Eigen::Matrix3d PlaneMoments::covariance() const
{
  const Eigen::Vector3d mu = mean();
  Eigen::Matrix3d c;
  c(0, 0) = xx / count - mu.x() * mu.x();
  c(0, 1) = xy / count - mu.x() * mu.y();
  c(0, 2) = xz / count - mu.x() * mu.z();
  c(1, 1) = yy / count - mu.y() * mu.y();
  c(1, 2) = yz / count - mu.y() * mu.z();
  c(2, 2) = zz / count - mu.z() * mu.z();
  c(1, 0) = c(0, 1);
  c(2, 0) = c(0, 2);
  c(2, 1) = c(1, 2);
  return c;
}

double MomentPlane::meanSquaredDistance(const PlaneMoments& moments) const
{
  // E[(n.(p - c))^2] = n^T Cov n + (n.(mean - c))^2
  const double offset = normal.dot(moments.mean() - centroid_m);
  return normal.dot(moments.covariance() * normal) + offset * offset;
}

MomentPlane fitMomentPlane(const PlaneMoments& moments)
{
  MomentPlane plane;
  plane.count = moments.count;
  if (moments.count < 3.0) return plane;
  plane.centroid_m = moments.mean();
  // Closed-form 3x3 eigen decomposition: the clustering fits one plane per
  // block and per merge, tens of thousands per frame.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver;
  solver.computeDirect(moments.covariance());
  const Eigen::Vector3d eigenvalues = solver.eigenvalues();  // ascending
  // Collinear points (a single row of pixels) leave two eigenvalues at zero.
  if (!(eigenvalues(1) > 1e-12 * std::max(1.0, eigenvalues(2))) || !std::isfinite(eigenvalues(2))) return plane;
  plane.normal = solver.eigenvectors().col(0).normalized();
  if (plane.normal.dot(plane.centroid_m) > 0.0) plane.normal = -plane.normal;
  plane.mse_m2 = std::max(0.0, eigenvalues(0));
  plane.narrow_variance_m2 = eigenvalues(1);
  plane.valid = plane.normal.allFinite();
  return plane;
}
MomentPlane refitMomentPlane(const PlaneMoments& moments, const Eigen::Vector3d& normal_guess)
{
  if (moments.count < 3.0) return fitMomentPlane(moments);
  const Eigen::Matrix3d c = moments.covariance();
  // adj(C) n is C^-1 n scaled by det(C): the same direction without the
  // division, and still defined when the points are exactly planar.
  Eigen::Matrix3d adjugate;
  adjugate(0, 0) = c(1, 1) * c(2, 2) - c(1, 2) * c(1, 2);
  adjugate(0, 1) = c(0, 2) * c(1, 2) - c(0, 1) * c(2, 2);
  adjugate(0, 2) = c(0, 1) * c(1, 2) - c(0, 2) * c(1, 1);
  adjugate(1, 1) = c(0, 0) * c(2, 2) - c(0, 2) * c(0, 2);
  adjugate(1, 2) = c(0, 1) * c(0, 2) - c(0, 0) * c(1, 2);
  adjugate(2, 2) = c(0, 0) * c(1, 1) - c(0, 1) * c(0, 1);
  adjugate(1, 0) = adjugate(0, 1);
  adjugate(2, 0) = adjugate(0, 2);
  adjugate(2, 1) = adjugate(1, 2);
  Eigen::Vector3d normal = normal_guess;
  for (int step = 0; step < 2; ++step)
  {
    const Eigen::Vector3d next = adjugate * normal;
    const double length = next.norm();
    if (!(length > 1e-300)) return fitMomentPlane(moments);
    normal = next / length;
  }
  // The in-plane 2 x 2 covariance gives the two larger eigenvalues.
  const Eigen::Vector3d u_axis = normal.unitOrthogonal(), v_axis = normal.cross(u_axis);
  const double cuu = u_axis.dot(c * u_axis), cvv = v_axis.dot(c * v_axis), cuv = u_axis.dot(c * v_axis);
  const double half_sum = 0.5 * (cuu + cvv), half_difference = 0.5 * (cuu - cvv);
  const double narrow = half_sum - std::sqrt(half_difference * half_difference + cuv * cuv);
  const double mse = normal.dot(c * normal);
  // Converged only when the normal's variance is clearly the smallest.
  if (!(narrow > 4.0 * mse) || !(narrow > 1e-12)) return fitMomentPlane(moments);

  MomentPlane plane;
  plane.count = moments.count;
  plane.centroid_m = moments.mean();
  plane.normal = normal.dot(plane.centroid_m) > 0.0 ? -normal : normal;
  plane.mse_m2 = std::max(0.0, mse);
  plane.narrow_variance_m2 = narrow;
  plane.valid = plane.normal.allFinite();
  return plane;
}
}  // namespace brick_pose
