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

/// The 24 proper rotations that map the coordinate axes onto (signed)
/// coordinate axes: the rotations of a cube, identity first.
std::vector<Eigen::Matrix3d> axisAlignedRotations();

/// The rigid motions of the brick frame that map a cuboid of `dimensions_m`
/// (length x, width y, height z; origin at the top-face centre, body below)
/// onto itself: rotations about the cuboid's centre (0, 0, -height / 2). Four
/// for three different dimensions, eight when two are equal (within
/// tolerance_m; e.g. a 0.2 x 0.2 cross-section), 24 for a cube. Identity first.
/// A surface registration cannot tell these apart, so a whole-cuboid pose is
/// right or wrong only modulo them.
std::vector<Eigen::Isometry3d> cuboidSymmetries(const Eigen::Vector3d& dimensions_m, double tolerance_m = 1e-3);

/// Rotation angle of estimate^-1 * truth, minimised over the symmetry group,
/// and the distance between the two origins (face centres).
PoseError poseErrorModuloSymmetry(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                  ModelSymmetry symmetry = ModelSymmetry::kHalfTurnZ);
/// The error of `estimate` against truth * S for the symmetry S (in the
/// brick frame, see cuboidSymmetries) with the smallest rotation error; the
/// translation error is then the distance between the brick-frame origins
/// that estimate and truth * S put in the camera frame.
PoseError poseErrorModuloSymmetries(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth,
                                    const std::vector<Eigen::Isometry3d>& symmetries);
}  // namespace registration
}  // namespace brick_pose
