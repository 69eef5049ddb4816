#pragma once
// The local polish of a Super4PCS pose (super4pcs.h): a coarse symmetric
// hybrid ICP on small samples (symmetric_icp.h), then a boundary ICP
// (boundary_icp.h) that takes the position and rotation within the surface
// from the boundaries of both clouds. Shared by the face registration and the
// whole-view registration (which polishes with the model's visible faces).

#include <chrono>
#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/common/elapsed.h"
#include "brick_pose/registration/point_set.h"
#include "brick_pose/registration/super4pcs.h"

namespace brick_pose
{
namespace registration
{
/// The tolerances that follow from the parameters and the sample density.
struct SearchScales
{
  double target_sample_spacing_m = 0.0;
  double pair_tolerance_m = 0.0;
  double lcp_radius_m = 0.0;
  double source_diameter_m = 0.0;
};

/// Whether the refined pose still covers the target about as well as the
/// 4-point pose did (scored at a wider radius than the LCP's).
bool refinementKeepsCoverage(const std::vector<Eigen::Vector3d>& lcp_sample, const std::vector<Eigen::Vector3d>& target,
                             double lcp_radius_m, const Eigen::Isometry3d& four_point_pose,
                             const Eigen::Isometry3d& refined_pose);

/// An evenly spread sample of `cloud` with unit normals (estimated when the
/// caller gave none).
PointSet sampleWithNormals(const PointSet& cloud, int count, std::mt19937_64& rng);

/// The coarse stage, then the boundary stage, from `start_pose`; both stop
/// at params.max_time_s counted from `start`.
Eigen::Isometry3d polishWithIcp(const PointSet& source, const PointSet& target, const Eigen::Isometry3d& start_pose,
                                const SearchScales& scales, const Super4PCSParams& params,
                                SteadyClock::time_point start, std::mt19937_64& rng);
}  // namespace registration
}  // namespace brick_pose
