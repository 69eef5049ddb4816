#pragma once
// Least-squares rigid transform between corresponding points (Kabsch /
// Umeyama without scale), used for 4-point candidates and for refinement.

#include <vector>

#include <Eigen/Geometry>

namespace brick_pose
{
namespace registration
{
struct RigidFit
{
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();  ///< source -> target
  double rms_m = 0.0;  ///< residual of the fitted correspondences
  bool valid = false;  ///< false for fewer than 3 pairs or a degenerate (collinear) set
};

/// Best proper rotation and translation with target[i] ~ T * source[i].
RigidFit fitRigid(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target);
}  // namespace registration
}  // namespace brick_pose
