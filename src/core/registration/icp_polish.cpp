#include "brick_pose/registration/icp_polish.h"

#include <algorithm>

#include "brick_pose/registration/boundary_icp.h"
#include "brick_pose/registration/lcp_scorer.h"
#include "brick_pose/registration/normal_estimation.h"
#include "brick_pose/registration/symmetric_icp.h"
#include "brick_pose/registration/uniform_sampling.h"

namespace brick_pose
{
namespace registration
{
namespace
{
// In-surface tolerance of target -> source ICP pairs over the (dense, clean)
// source sample's spacing; measured best of 0.75 and 1.0 on the benchmark.
constexpr double kReverseTolerancePerSpacing = 0.75;
// Neighbours of a point in boundary detection: enough that the centroid of
// an interior neighbourhood stays close to its point.
constexpr int kBoundaryNeighbours = 20;
// Target points farther off the source surface than this many robust
// standard deviations of the depth noise take no part in the target boundary.
constexpr double kOnSurfaceSigmas = 3.0;
}  // namespace

/// Whether the refined pose still covers the target about as well as the
/// 4-point pose did; if not, the refinement was pulled off by clutter. The
/// question is not which pose is more precise, so the coverage is scored at
/// a wider radius than the LCP's: at the LCP's own radius the right pose can
/// score lower than a 4-point pose a centimetre off, where the target has
/// holes (depth lost to stereo) and flying pixels beyond an edge that the
/// wrong pose happens to cover.
bool refinementKeepsCoverage(const std::vector<Eigen::Vector3d>& lcp_sample, const std::vector<Eigen::Vector3d>& target,
                             double lcp_radius_m, const Eigen::Isometry3d& four_point_pose,
                             const Eigen::Isometry3d& refined_pose)
{
  // Kept unless its coverage, scored at this many LCP radii, drops by more
  // than this below the 4-point pose's.
  constexpr double kGuardRadiusPerLcpRadius = 2.0;
  constexpr double kMaxCoverageDropByRefinement = 0.03;
  const LcpScorer coverage(lcp_sample, target, kGuardRadiusPerLcpRadius * lcp_radius_m);
  return coverage.score(refined_pose) >= coverage.score(four_point_pose) - kMaxCoverageDropByRefinement;
}

/// An evenly spread sample of `cloud` with unit normals (estimated when the
/// caller gave none; callers' normals need not be unit).
PointSet sampleWithNormals(const PointSet& cloud, int count, std::mt19937_64& rng)
{
  PointSet sample = cloud.subset(uniformSubsample(cloud.points, count, rng));
  if (!sample.hasNormals())
    sample.normals =
        estimateNormals(sample.points, kNormalRadiusPerSpacing * neighbourSpacing(sample.points, 0.5, rng));
  for (Eigen::Vector3d& normal : sample.normals)
    if (normal.squaredNorm() > 0.0)
      normal.normalize();
  return sample;
}

namespace
{
/// Stage 1: symmetric hybrid ICP on small samples from the 4-point pose,
/// with a wide radius that shrinks: it pulls the pose onto the surface and
/// most of the way in the plane, cheaply.
Eigen::Isometry3d coarseIcp(const PointSet& refine_source, const std::vector<Eigen::Vector3d>& refine_target,
                            const Eigen::Isometry3d& start_pose, double start_radius_m, const SearchScales& scales,
                            const Super4PCSParams& params, double remaining_s, std::mt19937_64& rng)
{
  const double target_spacing_m = neighbourSpacing(refine_target, 0.5, rng);
  SymmetricIcpParams icp;
  icp.final_radius_m = std::max(1.5 * scales.lcp_radius_m, 1.5 * target_spacing_m);  // the LCP's resolution
  icp.radius_m = std::max(start_radius_m, icp.final_radius_m);
  icp.in_surface_tolerance_m = std::max(params.delta_m, target_spacing_m);
  icp.final_in_surface_tolerance_m = icp.in_surface_tolerance_m;
  icp.reverse_in_surface_tolerance_m =
      std::max(params.delta_m, kReverseTolerancePerSpacing * neighbourSpacing(refine_source.points, 0.5, rng));
  icp.max_iterations = params.refine_iterations;
  icp.max_time_s = remaining_s;
  // Steps below a fiftieth of the accuracy change nothing that matters.
  icp.min_step_m = 0.02 * params.delta_m;
  icp.min_step_rad = icp.min_step_m / std::max(scales.source_diameter_m, 1e-9);
  return refineSymmetricIcp(refine_source.points, refine_source.normals, refine_target, start_pose, icp);
}

/// What the boundary stage registers: a dense target sample, the target's
/// boundary and the source's.
struct BoundaryStageInput
{
  std::vector<Eigen::Vector3d> target_sample;
  SurfaceBoundary target_boundary;
  SurfaceBoundary source_boundary;
  double target_spacing_m = 0.0;  ///< 0: too few points for a boundary
  double source_spacing_m = 0.0;
};

/// The boundaries of a dense source sample (a clean source, a model, then
/// keeps its exact edge points) and of the target's points that lie on the
/// source surface at `pose` (no flying pixels), in the plane of the source's
/// normals.
BoundaryStageInput findBoundaries(const PointSet& source, const PointSet& target, const PointSet& plane_source,
                                  const Eigen::Isometry3d& pose, double reach_m, const Super4PCSParams& params,
                                  std::mt19937_64& rng)
{
  BoundaryStageInput input;
  const PointSet source_sample =
      source.subset(uniformSubsample(source.points, params.fine_refine_source_sample_size, rng));
  input.source_spacing_m = neighbourSpacing(source_sample.points, 0.5, rng);
  input.target_sample = target.subset(uniformSubsample(target.points, params.fine_refine_sample_size, rng)).points;
  input.target_spacing_m = neighbourSpacing(input.target_sample, 0.5, rng);
  if (!(input.source_spacing_m > 0.0) || !(input.target_spacing_m > 0.0))
    return input;
  input.source_boundary = findSurfaceBoundary(source_sample.points, source_sample.normals,
                                              neighbourhoodRadius(source_sample.points, kBoundaryNeighbours, rng));
  const OrientedPoints on_surface =
      pointsOnSurface(plane_source.points, plane_source.normals, input.target_sample, pose,
                      2.0 * neighbourSpacing(plane_source.points, 0.5, rng),
                      std::max(reach_m, 3.0 * input.target_spacing_m), kOnSurfaceSigmas, 0.5 * params.delta_m);
  input.target_boundary = findSurfaceBoundary(on_surface.points, on_surface.normals,
                                              neighbourhoodRadius(on_surface.points, kBoundaryNeighbours, rng));
  return input;
}

/// Stage 2: boundary ICP (boundary_icp.h). Point-to-plane pairs on the
/// coarse stage's samples hold the surface; the boundaries of both clouds
/// give the in-surface position and rotation, which the hybrid step of
/// stage 1 leaves within a dead zone of about the target's sample spacing (it
/// cannot tell an edge that overhangs by less from sampling noise), and along
/// a long face the LCP hardly sees either.
Eigen::Isometry3d boundaryIcp(const PointSet& source, const PointSet& target, const PointSet& plane_source,
                              const Eigen::Isometry3d& start_pose, double boundary_start_radius_m,
                              const SearchScales& scales, const Super4PCSParams& params, SteadyClock::time_point start,
                              std::mt19937_64& rng)
{
  const BoundaryStageInput input =
      findBoundaries(source, target, plane_source, start_pose, boundary_start_radius_m, params, rng);
  if (!(input.target_spacing_m > 0.0) || !(input.source_spacing_m > 0.0))
    return start_pose;
  BoundaryIcpParams icp;
  // The coarse stage has brought the source onto the surface: the plane
  // pairs need no wider radius than the LCP's resolution.
  icp.final_plane_radius_m = std::max(1.5 * scales.lcp_radius_m, 1.5 * input.target_spacing_m);
  icp.plane_radius_m = icp.final_plane_radius_m;
  // A target boundary point lies up to about a target spacing inside the true
  // edge, and its nearest source boundary point up to half a source spacing
  // along the edge.
  icp.final_boundary_radius_m =
      std::max(params.delta_m, 1.5 * input.target_spacing_m + 0.5 * input.source_spacing_m);
  icp.boundary_radius_m = std::max(boundary_start_radius_m, icp.final_boundary_radius_m);
  icp.max_iterations = params.fine_refine_iterations;
  // What the boundary search left of the budget.
  icp.max_time_s = params.max_time_s - secondsSince(start);
  if (icp.max_time_s <= 0.0)
    return start_pose;
  icp.min_step_m = 0.02 * params.delta_m;
  icp.min_step_rad = icp.min_step_m / std::max(scales.source_diameter_m, 1e-9);
  return refineBoundaryIcp(plane_source.points, plane_source.normals, input.source_boundary, input.target_sample,
                           input.target_boundary, start_pose, icp);
}

}  // namespace

/// The local refinement of the best 4-point pose: the coarse stage, then the
/// boundary stage. Both stop at the time budget.
Eigen::Isometry3d polishWithIcp(const PointSet& source, const PointSet& target, const Eigen::Isometry3d& start_pose,
                                const SearchScales& scales, const Super4PCSParams& params, SteadyClock::time_point start,
                                std::mt19937_64& rng)
{
  const PointSet refine_source = sampleWithNormals(source, params.refine_source_sample_size, rng);
  const std::vector<Eigen::Vector3d> refine_target =
      target.subset(uniformSubsample(target.points, params.refine_sample_size, rng)).points;
  // Wide enough to reach from a 4-point pose that is off by the pair
  // tolerance at the base's ends or by several degrees in the plane of a face
  // (which the LCP hardly sees).
  const double start_radius_m = std::max(3.0 * scales.pair_tolerance_m, 0.08 * scales.source_diameter_m);
  Eigen::Isometry3d coarse_pose = start_pose;
  double remaining_s = params.max_time_s - secondsSince(start);
  if (params.refine_iterations > 0 && remaining_s > 0.0)
    coarse_pose =
        coarseIcp(refine_source, refine_target, start_pose, start_radius_m, scales, params, remaining_s, rng);
  remaining_s = params.max_time_s - secondsSince(start);
  if (params.fine_refine_iterations <= 0 || remaining_s <= 0.0)
    return coarse_pose;
  // The coarse stage leaves the pose close to the surface but possibly far
  // from the edges in the surface, as far as the 4-point pose was: the
  // boundary pairs start as wide as the coarse stage did.
  return boundaryIcp(source, target, refine_source, coarse_pose, start_radius_m, scales, params, start, rng);
}
}  // namespace registration
}  // namespace brick_pose
