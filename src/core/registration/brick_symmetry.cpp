#include "brick_pose/registration/brick_symmetry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace brick_pose
{
namespace registration
{
namespace
{
Eigen::Matrix3d halfTurn(const Eigen::Vector3d& axis) { return Eigen::AngleAxisd(M_PI, axis).toRotationMatrix(); }
}  // namespace

std::vector<Eigen::Matrix3d> symmetryRotations(ModelSymmetry symmetry)
{
  std::vector<Eigen::Matrix3d> rotations{Eigen::Matrix3d::Identity()};
  if (symmetry == ModelSymmetry::kNone)
    return rotations;
  rotations.push_back(halfTurn(Eigen::Vector3d::UnitZ()));
  if (symmetry == ModelSymmetry::kRectangle)
  {
    rotations.push_back(halfTurn(Eigen::Vector3d::UnitX()));
    rotations.push_back(halfTurn(Eigen::Vector3d::UnitY()));
  }
  return rotations;
}

Eigen::Isometry3d canonicalisePose(const Eigen::Isometry3d& camera_from_brick, ModelSymmetry symmetry)
{
  Eigen::Isometry3d pose = camera_from_brick;
  if (symmetry == ModelSymmetry::kNone)
    return pose;
  if (symmetry == ModelSymmetry::kRectangle && pose.linear()(2, 2) > 0.0)
    pose.linear() = pose.linear() * halfTurn(Eigen::Vector3d::UnitX());
  // Round-off must not decide a tie: components this small count as zero.
  constexpr double kTie = 1e-9;
  const Eigen::Vector3d x_axis = pose.linear().col(0);
  if (x_axis.x() < -kTie || (std::abs(x_axis.x()) <= kTie && x_axis.y() < 0.0))
    pose.linear() = pose.linear() * halfTurn(Eigen::Vector3d::UnitZ());
  return pose;
}

PoseError poseErrorModuloSymmetry(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                  ModelSymmetry symmetry)
{
  PoseError error;
  error.rotation_deg = std::numeric_limits<double>::infinity();
  for (const Eigen::Matrix3d& s : symmetryRotations(symmetry))
  {
    const Eigen::Matrix3d difference = estimate.linear().transpose() * truth.linear() * s;
    const double cos_angle = std::clamp(0.5 * (difference.trace() - 1.0), -1.0, 1.0);
    error.rotation_deg = std::min(error.rotation_deg, std::acos(cos_angle) * 180.0 / M_PI);
  }
  error.translation_m = (estimate.translation() - truth.translation()).norm();
  return error;
}
}  // namespace registration
}  // namespace brick_pose
