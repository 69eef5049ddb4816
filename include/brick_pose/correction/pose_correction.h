#pragma once
// Constant-time correction of a registration pose from the measured top face
// (paper, section "Pose Error Estimation and Correction").
//
// The registration pose T_cam_brick maps brick-frame points (origin at the
// centre of the top face, x along the long edge, z out of the face) into the
// camera optical frame. The measured face gives the true long-edge direction
// (T1->T2), the true face centre (midpoint of T1 and T2) and, in `full` mode,
// the true face normal. The correction rotates and shifts the pose so that
// the model agrees with them; it never looks at the point cloud, so its cost
// does not depend on the number of points.

#include <Eigen/Geometry>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/correction/correction_mode.h"
#include "brick_pose/correction/measured_face.h"

namespace brick_pose
{
/// Limits beyond which the input is rejected as degenerate (InputError).
struct PoseCorrectionParams
{
  CorrectionMode mode = CorrectionMode::kFull;
  /// T1 and T2 closer than this give no usable direction.
  double min_t1_t2_separation_m = 0.01;
  /// T1 and T2 further apart than the brick's length plus this are not on one face.
  double max_t1_t2_excess_m = 0.02;
  /// T1->T2 must lie within this angle of the face plane (it should lie in it).
  double max_t1_t2_out_of_plane_deg = 30.0;
  /// Faces seen more obliquely than this (normal vs line of sight) are rejected.
  double max_viewing_angle_deg = 85.0;
  /// `full` mode: the largest roll/pitch correction accepted (measured normal
  /// vs the pose's z axis); beyond it the registration is wrong, not noisy.
  double max_tilt_correction_deg = 30.0;
};

/// The corrected pose and what was applied to get it.
struct PoseCorrection
{
  /// Corrected T_cam_brick.
  Eigen::Isometry3d corrected_pose = Eigen::Isometry3d::Identity();
  /// The right-multiplied matrix of the paper's FinalPose = Pose x delta,
  /// i.e. delta = Pose^-1 x FinalPose, in the registration's brick frame.
  Eigen::Isometry3d delta_in_brick = Eigen::Isometry3d::Identity();
  /// Rotation about the face normal, in (-pi/2, pi/2]; positive turns the
  /// model's x axis toward its y axis.
  double yaw_rad = 0.0;
  /// Roll/pitch removed in `full` mode (angle between the pose's z axis and
  /// the measured normal); always 0 in `paper` mode.
  double tilt_rad = 0.0;
  /// Shift of the brick origin, camera frame: corrected minus registered.
  Eigen::Vector3d offset_m = Eigen::Vector3d::Zero();
  CorrectionMode mode = CorrectionMode::kFull;

  double yawDeg() const;
  double tiltDeg() const;
};

/// Corrects `T_cam_brick` so that the model's top face matches `face`.
///
/// `paper`: yaw about the pose's z axis by the angle from A1->A2 (model
/// origin to a point on its x axis) to T1->T2, then the translation that puts
/// the model origin on the midpoint of T1 and T2. `full`: first the minimal
/// rotation taking the pose's z axis onto the measured normal, then the yaw
/// about that normal, then the translation onto the midpoint projected onto
/// the fitted plane. The face is symmetric under a half turn, so T1->T2 is
/// taken in whichever sense makes the yaw the small angle.
///
/// Throws InputError naming the problem for non-finite values, a pose that is
/// not a rigid transform, T1 = T2, a zero normal or one facing away from or
/// perpendicular to the line of sight, T1->T2 along the normal, or a tilt
/// beyond the limit; ConfigError for a brick without a positive length.
PoseCorrection correctPose(const Eigen::Isometry3d& T_cam_brick, const BrickType& brick, const MeasuredFace& face,
                           const PoseCorrectionParams& parameters = PoseCorrectionParams());
}  // namespace brick_pose
