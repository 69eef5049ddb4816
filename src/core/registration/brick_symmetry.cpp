#include "brick_pose/registration/brick_symmetry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "brick_pose/common/angles.h"

namespace brick_pose
{
namespace registration
{
namespace
{
Eigen::Matrix3d halfTurn(const Eigen::Vector3d& axis) { return Eigen::AngleAxisd(M_PI, axis).toRotationMatrix(); }

double rotationAngleDeg(const Eigen::Matrix3d& difference)
{
  const double cos_angle = std::clamp(0.5 * (difference.trace() - 1.0), -1.0, 1.0);
  return std::acos(cos_angle) * kRadToDeg;
}
}  // namespace

std::vector<Eigen::Matrix3d> axisAlignedRotations()
{
  std::vector<Eigen::Matrix3d> rotations{Eigen::Matrix3d::Identity()};
  const int permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const auto& permutation : permutations)
    for (int signs = 0; signs < 8; ++signs)
    {
      Eigen::Matrix3d rotation = Eigen::Matrix3d::Zero();
      for (int column = 0; column < 3; ++column)
        rotation(permutation[column], column) = (signs >> column) & 1 ? -1.0 : 1.0;
      if (rotation.determinant() > 0.0 && !rotation.isIdentity())
        rotations.push_back(rotation);
    }
  return rotations;
}

std::vector<Eigen::Isometry3d> cuboidSymmetries(const Eigen::Vector3d& dimensions_m, double tolerance_m)
{
  const Eigen::Vector3d centre(0.0, 0.0, -0.5 * dimensions_m.z());
  std::vector<Eigen::Isometry3d> symmetries;
  for (const Eigen::Matrix3d& rotation : axisAlignedRotations())
  {
    // The rotated box has the extents |R| * dimensions; a symmetry keeps them.
    const Eigen::Vector3d rotated_extent = rotation.cwiseAbs() * dimensions_m;
    if (!((rotated_extent - dimensions_m).cwiseAbs().maxCoeff() <= tolerance_m))
      continue;
    Eigen::Isometry3d symmetry = Eigen::Isometry3d::Identity();
    symmetry.linear() = rotation;
    symmetry.translation() = centre - rotation * centre;
    symmetries.push_back(symmetry);
  }
  return symmetries;
}

PoseError poseErrorModuloSymmetries(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                    const std::vector<Eigen::Isometry3d>& symmetries)
{
  PoseError best;
  best.rotation_deg = std::numeric_limits<double>::infinity();
  best.translation_m = std::numeric_limits<double>::infinity();
  const std::vector<Eigen::Isometry3d> identity{Eigen::Isometry3d::Identity()};
  for (const Eigen::Isometry3d& symmetry : symmetries.empty() ? identity : symmetries)
  {
    const Eigen::Isometry3d equivalent = truth * symmetry;
    PoseError error;
    error.rotation_deg = rotationAngleDeg(estimate.linear().transpose() * equivalent.linear());
    error.translation_m = (estimate.translation() - equivalent.translation()).norm();
    if (error.rotation_deg < best.rotation_deg - 1e-9 ||
        (error.rotation_deg <= best.rotation_deg + 1e-9 && error.translation_m < best.translation_m))
      best = error;
  }
  return best;
}

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
    error.rotation_deg = std::min(error.rotation_deg, std::acos(cos_angle) * kRadToDeg);
  }
  error.translation_m = (estimate.translation() - truth.translation()).norm();
  return error;
}
}  // namespace registration
}  // namespace brick_pose
