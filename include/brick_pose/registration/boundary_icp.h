#pragma once
// Local refinement of a registration between surfaces with boundaries (the
// edges of a face, the rim of a partial view) by ICP with two residuals:
//  - point-to-plane for source points near the target surface: the distance
//    to the surface and the tilt;
//  - point-to-line for target boundary points near a source boundary point:
//    their offset along the source boundary's outward direction in the
//    surface. It fixes the position and rotation within the surface, which
//    point-to-plane leaves free and which on a long flat face nothing but the
//    boundary determines.
// Every residual is a distance along a known direction, so each step is a
// Gauss-Newton step that needs no dead zone for sampling noise (the hybrid
// step of symmetric_icp.h does) and converges in a few iterations even along
// a long face, where point-to-point ICP crawls.
//
// Boundary pairs run from the target to the source only. A target that sees
// part of the source has a rim the source lacks, whose points find no source
// boundary point nearby and are ignored; and the source boundary where the
// target is missing pulls nothing.

#include <limits>
#include <random>
#include <vector>

#include <Eigen/Geometry>

namespace brick_pose
{
namespace registration
{

/// Boundary points of a sampled surface.
struct SurfaceBoundary
{
  std::vector<Eigen::Vector3d> points;
  /// Unit, in the tangent plane, pointing away from the surface.
  std::vector<Eigen::Vector3d> outward;

  std::size_t size() const { return points.size(); }
};

/// The points whose neighbours within radius_m lie to one side of them in the
/// surface: the centroid of the neighbours, projected into the tangent plane,
/// is more than min_centroid_offset * radius_m away (about 0.42 on a straight
/// edge, near 0 inside). `normals` holds one normal per point, or is empty:
/// then each normal is estimated from the same neighbourhood. Points with
/// fewer than min_neighbours neighbours (isolated outliers) are never
/// boundary points. radius_m should be about 2.5 sample spacings.
SurfaceBoundary findSurfaceBoundary(const std::vector<Eigen::Vector3d>& points,
                                    const std::vector<Eigen::Vector3d>& normals, double radius_m,
                                    double min_centroid_offset = 0.3, int min_neighbours = 5);

/// Target points with the normal of the source surface under them.
struct OrientedPoints
{
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> normals;

  std::size_t size() const { return points.size(); }
};

/// The target points that lie on the source surface moved by
/// `source_to_target`: within max_sigmas robust standard deviations (from
/// the median absolute offset), and never less than min_offset_m, of the
/// tangent plane of their nearest source point within reach_m. Each keeps
/// that point's moved normal. Stereo depth puts "flying pixels" between an
/// edge and the background, off the surface but in the plane beyond the
/// edge, where a boundary search would take them for the edge. The nearest
/// source point is looked for within near_m first (a small radius is a cheap
/// query), then within reach_m.
OrientedPoints pointsOnSurface(const std::vector<Eigen::Vector3d>& source,
                               const std::vector<Eigen::Vector3d>& source_normals,
                               const std::vector<Eigen::Vector3d>& target, const Eigen::Isometry3d& source_to_target,
                               double near_m, double reach_m, double max_sigmas, double min_offset_m);

/// A radius that holds about `neighbours` points around a typical point:
/// the median, over up to `probes` points drawn with `rng`, of the distance
/// to their neighbours-th nearest neighbour (0 for too few points). Unlike a
/// multiple of the nearest-neighbour spacing it does not depend on how
/// regular the sampling is (a voxel-thinned depth image is clumpier than a
/// grid, and its nearest neighbours are closer for the same density).
double neighbourhoodRadius(const std::vector<Eigen::Vector3d>& points, int neighbours, std::mt19937_64& rng,
                          int probes = 32);

struct BoundaryIcpParams
{
  /// Source -> target point-to-plane pairs farther apart are dropped; the
  /// radius shrinks geometrically from the first to the second value over
  /// the iterations (wide to pull in, narrow to ignore what does not overlap).
  double plane_radius_m = 0.03;
  double final_plane_radius_m = 0.015;
  /// The same for target boundary -> source boundary pairs. The start must
  /// reach across the initial in-surface error.
  double boundary_radius_m = 0.05;
  double final_boundary_radius_m = 0.02;
  int max_iterations = 10;
  /// Wall-clock budget of the call; no new iteration starts after it.
  double max_time_s = std::numeric_limits<double>::infinity();
  /// Convergence: translation and rotation of one step.
  double min_step_m = 1e-5;
  double min_step_rad = 1e-5;
};

/// The refined source -> target transform, starting from `start`.
/// source_normals holds one unit normal per source point; source_boundary
/// is in the source frame, target_boundary in the target frame. A target
/// boundary point pairs with the nearest source boundary point whose outward
/// direction (moved) is within 60 degrees of its own: a boundary point of
/// one side of a face never pulls the opposite side, and a spurious one
/// inside the target (noise, a hole) rarely finds a partner.
Eigen::Isometry3d refineBoundaryIcp(const std::vector<Eigen::Vector3d>& source,
                                    const std::vector<Eigen::Vector3d>& source_normals,
                                    const SurfaceBoundary& source_boundary, const std::vector<Eigen::Vector3d>& target,
                                    const SurfaceBoundary& target_boundary, const Eigen::Isometry3d& start,
                                    const BoundaryIcpParams& options);
}  // namespace registration
}  // namespace brick_pose
