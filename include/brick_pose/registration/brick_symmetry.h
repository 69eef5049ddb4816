#pragma once
// Symmetry of the brick models. The top-face rectangle looks the same after a
// half turn about its normal, and a face seen without normals also after a
// flip of the normal, so a registered pose is only defined up to these; the
// canonical form and the errors below take that into account.

#include <vector>

#include <Eigen/Geometry>

namespace brick_pose
{
namespace registration
{
enum class ModelSymmetry
{
  kNone,  ///< {I}
  kHalfTurnZ,  ///< {I, Rz(180)}: the top face with normals, or a cuboid model
  kRectangle  ///< {I, Rz(180), Rx(180), Ry(180)}: a bare rectangle (normal flips too)
};

/// Rotations (in the brick frame) that map the model onto itself.
std::vector<Eigen::Matrix3d> symmetryRotations(ModelSymmetry symmetry);

/// The representative of camera_from_brick that a rectangle symmetry allows:
/// the brick z axis points towards the camera (negative camera-frame z
/// component; flip with Rx(180) otherwise, only if `symmetry` is kRectangle),
/// then the brick x axis has a non-negative camera-frame x component (ties
/// broken by a non-negative y component; Rz(180) otherwise). The origin (face
/// centre) is fixed by every symmetry, so the translation is unchanged.
Eigen::Isometry3d canonicalisePose(const Eigen::Isometry3d& camera_from_brick,
                                   ModelSymmetry symmetry = ModelSymmetry::kRectangle);

struct PoseError
{
  double rotation_deg = 0.0;
  double translation_m = 0.0;
  double translation_mm() const { return 1000.0 * translation_m; }
};

/// Rotation angle of estimate^-1 * truth, minimised over the symmetry group,
/// and the distance between the two origins (face centres).
PoseError poseErrorModuloSymmetry(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                  ModelSymmetry symmetry = ModelSymmetry::kHalfTurnZ);
}  // namespace registration
}  // namespace brick_pose
