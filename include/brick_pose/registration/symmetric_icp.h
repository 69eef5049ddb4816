#pragma once
// Local refinement of a registration by trimmed, symmetric point-to-point ICP.
//
// Correspondences run both ways (source -> nearest target and target ->
// nearest source): on a flat face only the boundary fixes the in-plane pose,
// and one-way matching lets a source that overhangs the target's edge slide
// freely. Pairs farther apart than the radius are ignored, so target points
// the source does not cover (partial overlap, clutter) cannot pull it.
//
// With source normals the step is a hybrid of point-to-plane and
// point-to-point: a pair whose offset along the surface is within the sampling
// spacing constrains only the distance to the surface (its in-surface offset
// is sampling noise), a pair offset further along the surface (an edge that
// overhangs) pulls point-to-point. Plain point-to-point lets the many interior
// pairs hold the pose where it is, so sliding along a long face converges
// very slowly; the hybrid takes the slide from the edges alone.

#include <limits>
#include <vector>

#include <Eigen/Geometry>

namespace brick_pose
{
namespace registration
{
struct SymmetricIcpParams
{
  /// Correspondences farther apart are dropped. The radius shrinks
  /// geometrically from radius_m to final_radius_m over the iterations: wide
  /// to pull in from a coarse start, narrow to ignore what does not overlap.
  double radius_m = 0.02;
  double final_radius_m = 0.01;
  int max_iterations = 20;  ///< all iterations, including the point-to-point ones
  /// Wall-clock budget of the call; no new iteration starts after it.
  double max_time_s = std::numeric_limits<double>::infinity();
  double min_step_m = 1e-5;  ///< convergence: translation of one step
  double min_step_rad = 1e-5;  ///< convergence: rotation of one step
  /// Offsets along the surface up to this are sampling noise (hybrid step).
  /// It shrinks geometrically to final_in_surface_tolerance_m (when smaller)
  /// over the iterations: wide, the first steps slide fast along the surface;
  /// narrow, the last ones see edges that overhang by less than the spacing.
  double in_surface_tolerance_m = 0.005;
  double final_in_surface_tolerance_m = 0.005;
  /// Source -> target pairs whose offset runs along the surface pull
  /// point-to-point (true) or are left out (false). Without them only target
  /// points the source does not cover pull along the surface, which is the
  /// right criterion when the source (a model) is larger than the target
  /// (a partial view): a source overhanging the target's edge is no error.
  bool forward_point_to_point = true;
  /// The same for target -> source pairs (whose offsets are sampling noise up
  /// to the *source* spacing); <= 0 means the same as in_surface_tolerance_m.
  /// A source denser than the target (a model can be) then resolves edges
  /// that the target's own spacing would blur.
  double reverse_in_surface_tolerance_m = 0.0;
  /// Optionally end with plain point-to-point iterations even with normals:
  /// the hybrid step leaves a dead zone of about the tolerance in the plane,
  /// where point-to-point settles where the overhangs on both sides balance.
  /// Off by default: on sampled brick faces the slow point-to-point steps did
  /// not pay off in a handful of iterations (measured, see the benchmark).
  int point_to_point_iterations = 0;
  /// Extrapolate along two consecutive steps whose directions agree to this
  /// cosine (see symmetric_icp.cpp); max_extrapolation = 0 disables it.
  double min_extrapolation_cos = 0.9;
  double max_extrapolation = 10.0;
};

/// The refined source -> target transform, starting from `start`.
/// source_normals is either empty (point-to-point) or one unit normal per
/// source point (hybrid step).
Eigen::Isometry3d refineSymmetricIcp(const std::vector<Eigen::Vector3d>& source,
                                     const std::vector<Eigen::Vector3d>& source_normals,
                                     const std::vector<Eigen::Vector3d>& target, const Eigen::Isometry3d& start,
                                     const SymmetricIcpParams& options);
}  // namespace registration
}  // namespace brick_pose
