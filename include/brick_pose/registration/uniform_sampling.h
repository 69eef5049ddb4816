#pragma once
// Spatially even subsampling. Random subsets leave holes and clumps; 4PCS
// needs every base point to have a counterpart near it in the other cloud,
// which depends on the largest gap, so samples are spread evenly instead.

#include <random>
#include <vector>

#include <Eigen/Core>

namespace brick_pose
{
namespace registration
{
/// At most `target_count` indices of `points` (all of them when there are
/// fewer), at most one per cell of a voxel grid whose size is tuned to the
/// count; which cells and which points represent them is drawn with `rng`.
/// Clouds with fewer than 4 points per wanted sample are sampled at random.
std::vector<int> uniformSubsample(const std::vector<Eigen::Vector3d>& points, int target_count, std::mt19937_64& rng);

/// The `quantile` (0..1) of the distances from a few random points to their
/// nearest neighbour, a measure of the sampling density (0 for fewer than 2
/// points). The median is the typical spacing; a high quantile is the radius
/// within which almost every spot of the surface has a point.
double neighbourSpacing(const std::vector<Eigen::Vector3d>& points, double quantile, std::mt19937_64& rng,
                        int probes = 64);

/// The largest distance between two points, exact on up to max_points
/// (a uniform subsample is measured beyond that).
double approximateDiameter(const std::vector<Eigen::Vector3d>& points, std::mt19937_64& rng, int max_points = 256);
}  // namespace registration
}  // namespace brick_pose
