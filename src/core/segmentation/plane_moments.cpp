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
}  // namespace brick_pose
