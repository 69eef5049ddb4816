#include "brick_pose/correction/pose_correction.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
// Below this a vector has no usable direction (metres or unit-less).
constexpr double kTinyLength = 1e-9;
// A rotation matrix whose R^T R differs from I by more than this is not one.
constexpr double kRigidTolerance = 1e-6;

std::string formatNumber(double value, int decimals)
{
  std::ostringstream text;
  text << std::fixed << std::setprecision(decimals) << value;
  return text.str();
}

[[noreturn]] void reject(const std::string& problem)
{
  throw InputError("pose correction: " + problem);
}

void requireFinite(const Eigen::Vector3d& value, const char* name)
{
  if (!value.allFinite())
    reject(std::string(name) + " is not finite (NaN or Inf)");
}

void requireRigid(const Eigen::Isometry3d& pose)
{
  if (!pose.matrix().allFinite())
    reject("registration pose is not finite (NaN or Inf)");
  const Eigen::Matrix3d rotation = pose.linear();
  const double orthogonality_error = (rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm();
  // Written so that NaN (from entries near 1e308) fails the test too.
  if (!(orthogonality_error <= kRigidTolerance) || !(rotation.determinant() > 0.0))
    reject("registration pose is not a rigid transform (rotation part not orthonormal with determinant +1)");
}

/// Angle (rad) between `direction` and the plane with unit normal `normal`.
double angleOutOfPlane(const Eigen::Vector3d& direction, const Eigen::Vector3d& normal)
{
  const double along_normal = std::abs(direction.normalized().dot(normal));
  return std::asin(std::min(1.0, along_normal));
}

Eigen::Vector3d projectOntoPlane(const Eigen::Vector3d& vector, const Eigen::Vector3d& unit_normal)
{
  return vector - unit_normal * unit_normal.dot(vector);
}

/// Signed angle (rad) about `unit_axis` from `from` to `to`, both projected
/// onto the plane normal to the axis, folded into (-pi/2, pi/2]: the face looks
/// the same after a half turn, so `to` and `-to` are the same measurement and
/// the smaller of the two rotations is the correction.
double smallSignedAngle(const Eigen::Vector3d& from, const Eigen::Vector3d& to, const Eigen::Vector3d& unit_axis)
{
  const Eigen::Vector3d from_in_plane = projectOntoPlane(from, unit_axis);
  const Eigen::Vector3d to_in_plane = projectOntoPlane(to, unit_axis);
  double angle_rad = std::atan2(unit_axis.dot(from_in_plane.cross(to_in_plane)), from_in_plane.dot(to_in_plane));
  if (angle_rad > kPi / 2.0)
    angle_rad -= kPi;
  else if (angle_rad <= -kPi / 2.0)
    angle_rad += kPi;
  return angle_rad;
}

/// Checks what both modes rely on and returns the unit face normal.
Eigen::Vector3d validateFace(const MeasuredFace& face, const BrickType& brick,
                             const PoseCorrectionParams& parameters)
{
  requireFinite(face.t1_m, "T1");
  requireFinite(face.t2_m, "T2");
  requireFinite(face.centroid_m, "face centroid");
  requireFinite(face.normal, "face normal");
  if (face.normal.norm() < kTinyLength)
    reject("face normal is zero");
  const Eigen::Vector3d normal = face.normal.normalized();

  const double separation_m = (face.t2_m - face.t1_m).norm();
  if (separation_m < parameters.min_t1_t2_separation_m)
    reject("T1 and T2 are " + formatNumber(separation_m * 1e3, 2) + " mm apart, less than the minimum " +
           formatNumber(parameters.min_t1_t2_separation_m * 1e3, 2) + " mm (T1 = T2 gives no direction)");
  if (separation_m > brick.length_m + parameters.max_t1_t2_excess_m)
    reject("T1 and T2 are " + formatNumber(separation_m, 3) + " m apart, longer than brick '" + brick.name +
           "' (" + formatNumber(brick.length_m, 3) + " m): they are not on one top face");

  // The camera is at the origin of the frame the face is measured in.
  const double distance_m = face.centroid_m.norm();
  if (distance_m < kTinyLength)
    reject("face centroid is at the camera origin");
  const double cos_viewing = normal.dot(-face.centroid_m / distance_m);
  const double cos_max_viewing = std::cos(parameters.max_viewing_angle_deg * kDegToRad);
  if (cos_viewing < -cos_max_viewing)
    reject("face normal points away from the camera (it must point toward it)");
  if (cos_viewing < cos_max_viewing)
    reject("face normal is nearly perpendicular to the line of sight (viewing angle " +
           formatNumber(std::acos(std::max(-1.0, std::min(1.0, cos_viewing))) * kRadToDeg, 1) + " deg, limit " +
           formatNumber(parameters.max_viewing_angle_deg, 1) + " deg)");

  const double out_of_plane_rad = angleOutOfPlane(face.t2_m - face.t1_m, normal);
  if (out_of_plane_rad > parameters.max_t1_t2_out_of_plane_deg * kDegToRad)
    reject("T1->T2 is " + formatNumber(out_of_plane_rad * kRadToDeg, 1) +
           " deg out of the face plane (limit " + formatNumber(parameters.max_t1_t2_out_of_plane_deg, 1) +
           " deg): it is (nearly) parallel to the face normal");
  return normal;
}

/// The paper's FinalPose = Pose x [Rz(theta) | delta_t'].
///
/// Where delta_t' lives: the right-multiplied matrix maps a brick point p to
/// Rz p + delta_t', which Pose = [R | t] then maps to R Rz p + R delta_t' + t.
/// The corrected origin (p = 0) must land on C1, so R delta_t' + t = C1, i.e.
/// delta_t' = R^T (C1 - C2) with C2 = t the transformed model origin: the
/// camera-frame error dt rotated into the registration's brick frame. It is
/// the frame *before* Rz because [Rz | delta_t'] applies the rotation first
/// and then the shift in the outer frame; written as Pose x Rz x Trans(d'')
/// the shift would instead be d'' = Rz^T R^T dt, the rotated brick frame.
PoseCorrection correctLikePaper(const Eigen::Isometry3d& pose, const BrickType& brick, const MeasuredFace& face,
                                const PoseCorrectionParams& parameters)
{
  const Eigen::Matrix3d& rotation = pose.linear();
  const Eigen::Vector3d pose_z = rotation.col(2);
  const Eigen::Vector3d measured_direction = face.t2_m - face.t1_m;
  if (angleOutOfPlane(measured_direction, pose_z) > parameters.max_t1_t2_out_of_plane_deg * kDegToRad)
    reject("T1->T2 is (nearly) parallel to the registration pose's z axis; no yaw can be measured about it");

  // A2 anywhere on the model's positive x axis inside the face; only the
  // direction A1->A2 matters.
  const Eigen::Vector3d a1 = pose * Eigen::Vector3d::Zero();
  const Eigen::Vector3d a2 = pose * Eigen::Vector3d(brick.length_m / 4.0, 0.0, 0.0);

  PoseCorrection result;
  result.mode = CorrectionMode::kPaper;
  result.yaw_rad = smallSignedAngle(a2 - a1, measured_direction, pose_z);
  result.offset_m = face.midpoint_m() - a1;  // dt = C1 - C2
  result.delta_in_brick.linear() = Eigen::AngleAxisd(result.yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  result.delta_in_brick.translation() = rotation.transpose() * result.offset_m;
  result.corrected_pose = pose * result.delta_in_brick;
  return result;
}

/// Six-DOF variant: tilt the pose's z onto the measured normal (minimal
/// rotation, about the origin of the brick), yaw about that normal, then move
/// the origin. The in-plane position comes from the T1/T2 midpoint, but the
/// distance along the normal from the least-squares plane: it averages every
/// point of the segment, while T1 and T2 are single depth samples. For exact
/// data the midpoint lies on the plane and both agree.
PoseCorrection correctAllSixDof(const Eigen::Isometry3d& pose, const MeasuredFace& face,
                                const Eigen::Vector3d& normal, const PoseCorrectionParams& parameters)
{
  const Eigen::Vector3d pose_z = pose.linear().col(2);
  PoseCorrection result;
  result.mode = CorrectionMode::kFull;
  result.tilt_rad = std::atan2(pose_z.cross(normal).norm(), pose_z.dot(normal));
  if (result.tilt_rad > parameters.max_tilt_correction_deg * kDegToRad)
    reject("face normal is " + formatNumber(result.tilt_rad * kRadToDeg, 1) +
           " deg from the registration pose's z axis (limit " +
           formatNumber(parameters.max_tilt_correction_deg, 1) + " deg): the registration is wrong, not tilted");

  const Eigen::Matrix3d untilted = Eigen::Quaterniond::FromTwoVectors(pose_z, normal) * pose.linear();
  result.yaw_rad = smallSignedAngle(untilted.col(0), face.t2_m - face.t1_m, normal);
  const Eigen::Matrix3d rotation = Eigen::AngleAxisd(result.yaw_rad, normal) * untilted;

  const Eigen::Vector3d midpoint = face.midpoint_m();
  const Eigen::Vector3d origin = midpoint - normal * normal.dot(midpoint - face.centroid_m);

  result.corrected_pose.linear() = rotation;
  result.corrected_pose.translation() = origin;
  result.offset_m = origin - pose.translation();
  result.delta_in_brick = pose.inverse(Eigen::Isometry) * result.corrected_pose;
  return result;
}
}  // namespace

double PoseCorrection::yawDeg() const
{
  return yaw_rad * kRadToDeg;
}

double PoseCorrection::tiltDeg() const
{
  return tilt_rad * kRadToDeg;
}

PoseCorrection correctPose(const Eigen::Isometry3d& T_cam_brick, const BrickType& brick, const MeasuredFace& face,
                           const PoseCorrectionParams& parameters)
{
  if (!(std::isfinite(brick.length_m) && brick.length_m > 0.0))
    throw ConfigError("pose correction: brick '" + brick.name + "' needs a positive length_m");
  requireRigid(T_cam_brick);
  const Eigen::Vector3d normal = validateFace(face, brick, parameters);
  PoseCorrection correction;
  switch (parameters.mode)
  {
    case CorrectionMode::kPaper:
      correction = correctLikePaper(T_cam_brick, brick, face, parameters);
      break;
    case CorrectionMode::kFull:
      correction = correctAllSixDof(T_cam_brick, face, normal, parameters);
      break;
    default:
      throw ConfigError("pose correction: unknown correction mode");
  }
  // Finite but absurd inputs (entries near 1e308) overflow in the products.
  if (!correction.corrected_pose.matrix().allFinite())
    throw InputError("pose correction: the corrected pose overflowed (pose or face far out of range)");
  return correction;
}
}  // namespace brick_pose
