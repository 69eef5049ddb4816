#pragma once
// The `icp` refinement alternative: point-to-point ICP of the brick's top-face
// model against the segmented face cloud, started from the registration pose.
// O(n log n) per iteration, against correctPose()'s constant time; kept for
// comparison (the paper's Table 1) and for faces where T1/T2 are unreliable.

#include <Eigen/Geometry>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "brick_pose/catalogue/brick_catalogue.h"

namespace brick_pose
{
/// pcl::IterativeClosestPoint settings; the defaults suit registration errors
/// of a few degrees and millimetres on a D415 face cloud.
struct IcpParams
{
  /// Pairs further apart than this are ignored; a few times the expected
  /// registration error, well below the face's size.
  double max_correspondence_distance_m = 0.02;
  int max_iterations = 100;
  /// Stop when an iteration moves the pose by less than this: PCL compares
  /// it with the squared translation step (m^2) and 1 minus it with the
  /// cosine of the rotation step. On a plane ICP creeps in-plane by microns
  /// per iteration; 1e-10 (10 um steps) stopped it at twice the final error.
  double transformation_epsilon_m2 = 1e-12;
  /// Stop when the mean squared pair distance changes by less than this
  /// fraction of itself (PCL's euclidean fitness epsilon is relative).
  double relative_fitness_epsilon = 1e-9;
  /// Grid spacing of the top-face model cloud.
  double model_spacing_m = 0.005;
  /// Segment points ICP matches against, evenly thinned to about this many:
  /// a 1.2 m plate at 1.3 m is ~20k points, which only slows ICP down.
  int max_target_points = 2000;

  /// Throws ConfigError naming the first unusable field.
  void validate() const;
};

struct IcpRefinement
{
  /// Refined T_cam_brick (rotation re-orthonormalised after PCL's float
  /// maths); the initial pose itself when ICP did not converge.
  Eigen::Isometry3d refined_pose = Eigen::Isometry3d::Identity();
  /// Mean squared distance (m^2) from the aligned model points to their
  /// nearest segment points, counting pairs within the correspondence distance.
  double fitness_m2 = 0.0;
  bool converged = false;
};

/// Samples the top face of `brick` (brick frame, z = 0) on a grid and aligns
/// it to `segment_cloud` (camera frame) with ICP from `initial_pose`.
/// Non-finite segment points are ignored. Throws InputError for a non-finite
/// initial pose or fewer than 3 finite segment points, ConfigError for bad
/// parameters or a brick without a positive length and width.
IcpRefinement refinePoseWithIcp(const Eigen::Isometry3d& initial_pose, const BrickType& brick,
                                const pcl::PointCloud<pcl::PointXYZ>& segment_cloud,
                                const IcpParams& parameters = IcpParams());
}  // namespace brick_pose
