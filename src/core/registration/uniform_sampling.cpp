#include "brick_pose/registration/uniform_sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "brick_pose/registration/point_grid.h"

namespace brick_pose
{
namespace registration
{
namespace
{
std::uint64_t voxelKey(const Eigen::Vector3d& p, double inv_voxel)
{
  constexpr std::int64_t mask = (std::int64_t(1) << 21) - 1;
  constexpr double kLimit = 4.0e15;  // keeps the conversion to integer defined
  // NaN (0 * inf) to 0 first: converting NaN to an integer is undefined.
  const Eigen::Vector3d scaled = (p * inv_voxel).unaryExpr([](double x) { return std::isnan(x) ? 0.0 : x; });
  const Eigen::Vector3d cell = scaled.array().max(-kLimit).min(kLimit).floor();
  return (static_cast<std::uint64_t>(static_cast<std::int64_t>(cell.x()) & mask) << 42) |
         (static_cast<std::uint64_t>(static_cast<std::int64_t>(cell.y()) & mask) << 21) |
         static_cast<std::uint64_t>(static_cast<std::int64_t>(cell.z()) & mask);
}

/// Voxels holding at least two points: the surface's voxels, not those of
/// isolated outliers (which would otherwise drive the voxel size).
std::size_t denseVoxels(const std::vector<Eigen::Vector3d>& points, double voxel_m)
{
  std::vector<std::uint64_t> keys(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    keys[i] = voxelKey(points[i], 1.0 / voxel_m);
  std::sort(keys.begin(), keys.end());
  std::size_t dense = 0;
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i] == keys[i - 1] && (i == 1 || keys[i - 1] != keys[i - 2]))
      ++dense;
  return dense;
}
}  // namespace

std::vector<int> uniformSubsample(const std::vector<Eigen::Vector3d>& points, int target_count, std::mt19937_64& rng)
{
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  if (target_count <= 0 || points.size() <= static_cast<std::size_t>(target_count))
    return order;
  std::shuffle(order.begin(), order.end(), rng);
  // With few points per voxel a grid cannot even anything out.
  if (points.size() < 4 * static_cast<std::size_t>(target_count))
  {
    order.resize(static_cast<std::size_t>(target_count));
    std::sort(order.begin(), order.end());
    return order;
  }

  Eigen::Vector3d lower = points.front();
  Eigen::Vector3d upper = points.front();
  for (const Eigen::Vector3d& p : points)
  {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  // Start from the spacing of a flat sheet over the two largest extents and
  // correct assuming the count scales like 1 / voxel^2 (surfaces).
  Eigen::Vector3d extent = (upper - lower).cwiseMax(1e-9);
  std::sort(extent.data(), extent.data() + 3);
  double voxel_m = std::sqrt(extent(2) * extent(1) / target_count);
  for (int iteration = 0; iteration < 6; ++iteration)
  {
    const double ratio = std::max(1.0, static_cast<double>(denseVoxels(points, voxel_m))) / target_count;
    if (ratio > 0.85 && ratio < 1.15)
      break;
    voxel_m *= std::sqrt(ratio);
  }

  // Each voxel is represented by its first point in the shuffled order, and
  // voxels are taken in the order of those first points. That is the same as
  // walking the shuffled points and keeping each one whose voxel is new: a
  // voxel is reached with a probability that grows with its point count, so
  // isolated outliers are not favoured over the surface.
  std::vector<std::pair<std::uint64_t, int>> keyed(order.size());
  for (std::size_t rank = 0; rank < order.size(); ++rank)
    keyed[rank] = {voxelKey(points[order[rank]], 1.0 / voxel_m), static_cast<int>(rank)};
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> first_ranks;
  for (std::size_t k = 0; k < keyed.size(); ++k)
    if (k == 0 || keyed[k].first != keyed[k - 1].first)
      first_ranks.push_back(keyed[k].second);
  std::sort(first_ranks.begin(), first_ranks.end());
  if (first_ranks.size() > static_cast<std::size_t>(target_count))
    first_ranks.resize(static_cast<std::size_t>(target_count));
  std::vector<int> kept;
  kept.reserve(first_ranks.size());
  for (int rank : first_ranks)
    kept.push_back(order[rank]);
  std::sort(kept.begin(), kept.end());
  return kept;
}

namespace
{
// Below this many points per probe a scan over all points is cheaper than
// building a grid.
constexpr std::size_t kMinPointsPerProbeForGrid = 4;
// Grid search radius over the spacing of a flat sheet spanning the two largest
// extents: surfaces folded over faces are denser than that sheet, so almost
// every probe finds its nearest neighbour inside.
constexpr double kSearchRadiusPerSheetSpacing = 2.0;

/// Squared distance from points[i] to its nearest point at a non-zero
/// distance (infinity when there is none), by scanning all points.
double nearestSqByScan(const std::vector<Eigen::Vector3d>& points, std::size_t i)
{
  double best_sq = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < points.size(); ++j)
  {
    const double d_sq = (points[j] - points[i]).squaredNorm();
    if (j != i && d_sq > 0.0 && d_sq < best_sq)
      best_sq = d_sq;
  }
  return best_sq;
}

/// The grid search radius for `points`; 0 when no grid should be used.
double gridSearchRadius(const std::vector<Eigen::Vector3d>& points, int probe_count)
{
  if (points.size() < kMinPointsPerProbeForGrid * static_cast<std::size_t>(probe_count))
    return 0.0;
  Eigen::Vector3d lower = points.front();
  Eigen::Vector3d upper = points.front();
  for (const Eigen::Vector3d& p : points)
  {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  Eigen::Vector3d extent = upper - lower;
  std::sort(extent.data(), extent.data() + 3);
  const double radius_m =
      kSearchRadiusPerSheetSpacing * std::sqrt(extent(2) * extent(1) / static_cast<double>(points.size()));
  return std::isfinite(radius_m) && radius_m > 0.0 ? radius_m : 0.0;
}
}  // namespace

double neighbourSpacing(const std::vector<Eigen::Vector3d>& points, double quantile, std::mt19937_64& rng,
                        int probes)
{
  if (points.size() < 2)
    return 0.0;
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  std::vector<double> nearest;
  const int probe_count = std::min<int>(probes, static_cast<int>(points.size()));
  // A nearest neighbour found within the radius is the nearest of all (any
  // nearer point is inside too), so the grid gives the scan's exact answer;
  // probes with nothing inside fall back to the scan.
  const double radius_m = gridSearchRadius(points, probe_count);
  const std::optional<PointGrid> grid =
      radius_m > 0.0 ? std::optional<PointGrid>(std::in_place, points, radius_m) : std::nullopt;
  for (int k = 0; k < probe_count; ++k)
  {
    const std::size_t i = pick(rng);
    double best_sq = std::numeric_limits<double>::infinity();
    if (grid)
      grid->forEachWithin(points[i], radius_m, [&](int j) {
        const double d_sq = (points[j] - points[i]).squaredNorm();
        if (static_cast<std::size_t>(j) != i && d_sq > 0.0 && d_sq < best_sq)
          best_sq = d_sq;
      });
    if (!std::isfinite(best_sq))
      best_sq = nearestSqByScan(points, i);
    if (std::isfinite(best_sq))
      nearest.push_back(std::sqrt(best_sq));
  }
  if (nearest.empty())
    return 0.0;
  const std::size_t rank = std::min(nearest.size() - 1, static_cast<std::size_t>(quantile * nearest.size()));
  std::nth_element(nearest.begin(), nearest.begin() + rank, nearest.end());
  return nearest[rank];
}

double approximateDiameter(const std::vector<Eigen::Vector3d>& points, std::mt19937_64& rng, int max_points)
{
  std::vector<int> subset = uniformSubsample(points, max_points, rng);
  double max_sq = 0.0;
  for (std::size_t a = 0; a < subset.size(); ++a)
    for (std::size_t b = a + 1; b < subset.size(); ++b)
      max_sq = std::max(max_sq, (points[subset[a]] - points[subset[b]]).squaredNorm());
  return std::sqrt(max_sq);
}
}  // namespace registration
}  // namespace brick_pose
