#pragma once
// Least-squares rigid transform between corresponding points (Kabsch /
// Umeyama without scale), used for 4-point candidates and for refinement.

#include <optional>
#include <vector>

#include <Eigen/Geometry>

namespace brick_pose
{
namespace registration
{
/// A small rigid motion (dt, dw) and the normal equations that solve for one.
using Twist = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The ICP variants drop offsets beyond this many median offsets as outliers
// (about 3 sigma for Gaussian noise: the median absolute value is 0.67 sigma),
// e.g. the flying pixels of stereo depth at an edge.
constexpr double kOutlierOffsetPerMedian = 4.5;

struct RigidFit
{
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();  ///< source -> target
  double rms_m = 0.0;  ///< residual of the fitted correspondences
  bool valid = false;  ///< false for fewer than 3 pairs or a degenerate (collinear) set
};

/// Best proper rotation and translation with target[i] ~ T * source[i].
RigidFit fitRigid(const std::vector<Eigen::Vector3d>& source, const std::vector<Eigen::Vector3d>& target);

/// The rigid step solving the linearised ICP normal equations lhs x = rhs,
/// x = (dt, dw): a point p moves by dt + dw x (p - centre). A tiny damping
/// keeps directions no residual constrains (e.g. the in-plane motion of a
/// face without edge pairs) still instead of letting round-off move them.
/// Nothing when the solution is not finite.
std::optional<Eigen::Isometry3d> solveRigidStep(Matrix6d lhs, const Twist& rhs, const Eigen::Vector3d& centre);
}  // namespace registration
}  // namespace brick_pose
