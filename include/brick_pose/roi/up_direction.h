#pragma once
// Which way is up in a frame. A top face is a brick's top only if it faces
// up; a robot knows "up" through tf (RoiFilterParams::up_direction, set from
// the nodelet's up_frame). Without it, the frame itself says: bricks and
// boxes rest on a supporting plane (the ground, a table, a pallet layer)
// that is the largest plane in view, and their tops are parallel to it.
// When no plane dominates, the segments' own normals are clustered and the
// heaviest cluster (by area) is taken: the tops of a pile face one way,
// each side face another.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "brick_pose/frame/rgbd_frame.h"

namespace brick_pose
{
enum class UpSource
{
  kUnknown,       ///< Nothing told: no face can be shown to be a top.
  kGiven,         ///< From tf (or the caller).
  kSupportPlane,  ///< The dominant plane of the frame.
  kFaceNormals,   ///< The area-weighted dominant normal of the frame's segments.
};

std::string toString(UpSource source);

struct UpDirection
{
  Eigen::Vector3d up = Eigen::Vector3d::Zero();  ///< Unit, camera frame; zero when unknown.
  UpSource source = UpSource::kUnknown;
  /// The dominant plane of the frame (the ground, a table), when it was
  /// found: unit normal toward the camera and offset (normal . p + offset =
  /// 0), and the share of the sampled depth pixels on it. Side faces that
  /// reach it are seen to the brick's foot.
  bool has_support_plane = false;
  Eigen::Vector3d support_normal = Eigen::Vector3d::Zero();
  double support_offset_m = 0.0;
  double support_fraction = 0.0;
  /// The supporting plane was given (tf), not estimated: it is what the
  /// pile stands on, so a face's height above it may tell its type.
  bool support_given = false;

  bool known() const { return source != UpSource::kUnknown; }
  /// Signed distance of a point above the supporting plane (0 without one).
  double heightAboveSupport(const Eigen::Vector3d& point_m) const
  {
    return has_support_plane ? support_normal.dot(point_m) + support_offset_m : 0.0;
  }
};

struct UpDirectionParams
{
  /// Depth pixels sampled on a grid this many pixels apart.
  int stride_px = 8;
  /// Plane hypotheses tried (three random samples each), each scored on
  /// score_points samples; the best is refitted on all its inliers.
  int iterations = 150;
  int score_points = 500;
  /// A sample is on the plane within max(inlier_distance_m,
  /// inlier_distance_per_m2 * depth^2) (depth noise grows with distance^2).
  double inlier_distance_m = 0.008;
  double inlier_distance_per_m2 = 0.004;
  /// The plane must hold at least this share of the samples to be the support.
  double min_support_fraction = 0.2;
  /// Face normals within this angle of each other form one cluster.
  double cluster_angle_deg = 15.0;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// The dominant plane's normal (oriented toward the camera) as "up", with
/// the plane itself; unknown when no plane holds min_support_fraction of the
/// samples. Deterministic (fixed seed).
UpDirection estimateSupportPlaneUp(const RgbdFrame& frame, const UpDirectionParams& params = UpDirectionParams());

/// The xy-plane of a frame posed at `camera_T_frame` (e.g. a pallet's deck
/// from tf), as (n, d) in the camera frame: n . p + d = 0, n its +z.
Eigen::Vector4d xyPlaneInCamera(const Eigen::Isometry3d& camera_T_frame);

/// Up and the supporting plane from a given plane (n, d), n . p + d = 0 in
/// the camera frame with n pointing up (need not be unit); unknown when n is
/// zero or not finite.
UpDirection givenSupport(const Eigen::Vector4d& plane);

/// `up` with its supporting plane replaced by the given `plane` (see
/// givenSupport), and its direction too when it had none; unchanged when
/// the plane is unknown.
UpDirection withGivenSupport(UpDirection up, const Eigen::Vector4d& plane);

/// The mean normal of the heaviest cluster of `normals` (unit, toward the
/// camera) weighted by `weights` (e.g. segment areas); unknown when empty.
UpDirection dominantFaceNormal(const std::vector<Eigen::Vector3d>& normals, const std::vector<double>& weights,
                               const UpDirectionParams& params = UpDirectionParams());
}  // namespace brick_pose
