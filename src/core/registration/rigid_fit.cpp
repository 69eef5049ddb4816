#include "brick_pose/registration/rigid_fit.h"

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/SVD>

namespace brick_pose
{
namespace registration
{
RigidFit fitRigid(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target)
{
  RigidFit fit;
  const std::size_t n = std::min(source.size(), target.size());
  if (n < 3)
    return fit;

  Eigen::Vector3d source_mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d target_mean = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    source_mean += source[i];
    target_mean += target[i];
  }
  source_mean /= static_cast<double>(n);
  target_mean /= static_cast<double>(n);

  Eigen::Matrix3d cross = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < n; ++i)
    cross += (source[i] - source_mean) * (target[i] - target_mean).transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(cross, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d singular = svd.singularValues();
  // Rank 1 (collinear points) leaves the rotation about the line free.
  if (!(singular(1) > 1e-12 * std::max(1.0, singular(0))))
    return fit;

  // The sign fix keeps the rotation proper: a mirror image of the source is
  // fitted as well as a rotation can, and its residual then rejects it.
  Eigen::Matrix3d sign = Eigen::Matrix3d::Identity();
  sign(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d rotation = svd.matrixV() * sign * svd.matrixU().transpose();

  fit.transform.linear() = rotation;
  fit.transform.translation() = target_mean - rotation * source_mean;
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    sum_sq += (fit.transform * source[i] - target[i]).squaredNorm();
  fit.rms_m = std::sqrt(sum_sq / static_cast<double>(n));
  fit.valid = true;
  return fit;
}

std::optional<Eigen::Isometry3d> solveRigidStep(Matrix6d lhs, const Twist& rhs, const Eigen::Vector3d& centre)
{
  lhs.diagonal().array() += 1e-9 * (lhs.trace() + 1.0);
  const Twist x = lhs.ldlt().solve(rhs);
  if (!x.allFinite())
    return std::nullopt;
  const Eigen::Vector3d dw = x.tail<3>();
  const double angle_rad = dw.norm();
  const Eigen::Matrix3d rotation =
      angle_rad > 0.0 ? Eigen::AngleAxisd(angle_rad, dw / angle_rad).toRotationMatrix() : Eigen::Matrix3d::Identity();
  Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
  step.linear() = rotation;
  step.translation() = centre + x.head<3>() - rotation * centre;
  return step;
}
}  // namespace registration
}  // namespace brick_pose
