#pragma once
// What the front end measured on the segmented top face, in the camera
// optical frame: the four vectors the constant-time correction works from.

#include <Eigen/Core>

namespace brick_pose
{
/// Geometry of one segmented top face, all in the camera frame (metres).
///
/// T1 and T2 lie on the face's long axis, equidistant from its centroid, so
/// that T1->T2 gives the face's long-edge direction up to sign and their
/// midpoint gives its centre. The correction is constant time because it sees
/// only these four vectors, never the cloud they were measured from.
struct MeasuredFace
{
  Eigen::Vector3d t1_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d t2_m = Eigen::Vector3d::Zero();
  /// Centroid of the segment cloud; a point of the fitted plane.
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  /// Least-squares plane normal of the segment, pointing toward the camera.
  /// Need not be exactly unit length; it is normalised before use.
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();

  Eigen::Vector3d midpoint_m() const { return 0.5 * (t1_m + t2_m); }
};
}  // namespace brick_pose
