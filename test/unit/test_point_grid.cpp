#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/registration/point_grid.h"
#include "brick_pose/registration/uniform_sampling.h"

namespace
{
using brick_pose::registration::PointGrid;

std::vector<Eigen::Vector3d> lattice()
{
  std::vector<Eigen::Vector3d> points;
  for (int x = 0; x < 5; ++x)
    for (int y = 0; y < 5; ++y)
      points.emplace_back(0.01 * x, 0.01 * y, 0.5);
  return points;
}
}  // namespace

TEST(PointGrid, FindsTheNearestPointWithinTheRadius)
{
  const std::vector<Eigen::Vector3d> points = lattice();
  const PointGrid grid(points, 0.004);
  EXPECT_EQ(grid.nearestWithin(Eigen::Vector3d(0.021, 0.029, 0.5), 0.004), 2 * 5 + 3);
  EXPECT_EQ(grid.nearestWithin(Eigen::Vector3d(0.015, 0.015, 0.5), 0.004), -1);
}

// A degenerate pose applied to a model point gives NaN or huge queries: they
// match nothing (and their cell index must not be computed from a NaN, which
// UBSan reports as an out-of-range conversion).
TEST(PointGrid, NaNAndHugeQueriesMatchNothing)
{
  const std::vector<Eigen::Vector3d> points = lattice();
  const PointGrid grid(points, 0.004);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& query :
       {Eigen::Vector3d(nan, 0.0, 0.5), Eigen::Vector3d(0.0, nan, nan), Eigen::Vector3d(inf, -inf, 0.5),
        Eigen::Vector3d(1e300, 0.0, 0.5), Eigen::Vector3d(-1e300, 1e300, -1e300)})
  {
    EXPECT_EQ(grid.nearestWithin(query, 0.004), -1);
    EXPECT_FALSE(grid.anyWithin(query, 0.004));
  }
}

// Clouds the input checks still accept (coordinates up to 1e6 m) next to a
// few millimetres: the voxel keys stay defined and the count is kept.
TEST(UniformSampling, KeepsTheCountOnACloudSpanningTheAllowedRange)
{
  std::vector<Eigen::Vector3d> points = lattice();
  points.emplace_back(1.0e6, -1.0e6, 1.0e6);
  points.emplace_back(-1.0e6, 1.0e6, 0.0);
  std::mt19937_64 rng(3);
  const std::vector<int> kept = brick_pose::registration::uniformSubsample(points, 8, rng);
  EXPECT_EQ(kept.size(), 8u);
  for (int index : kept)
  {
    EXPECT_GE(index, 0);
    EXPECT_LT(index, static_cast<int>(points.size()));
  }
}

namespace
{
/// neighbourSpacing's definition, by scanning every point: the quantile of
/// the distances from `probes` random points (drawn as neighbourSpacing draws
/// them) to their nearest point at a non-zero distance.
double spacingByScan(const std::vector<Eigen::Vector3d>& points, double quantile, std::uint64_t seed, int probes)
{
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  std::vector<double> nearest;
  for (int k = 0; k < probes; ++k)
  {
    const std::size_t i = pick(rng);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < points.size(); ++j)
    {
      const double d = (points[j] - points[i]).norm();
      if (j != i && d > 0.0)
        best = std::min(best, d);
    }
    if (std::isfinite(best))
      nearest.push_back(best);
  }
  std::sort(nearest.begin(), nearest.end());
  return nearest[std::min(nearest.size() - 1, static_cast<std::size_t>(quantile * nearest.size()))];
}
}  // namespace

// neighbourSpacing looks for neighbours in a grid; probes with none inside
// its radius (outliers far from the surface) and points with duplicates must
// still get the same answer as a scan over all points.
TEST(UniformSampling, NeighbourSpacingEqualsTheFullScanWithOutliersAndDuplicates)
{
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> sheet(0.0, 0.2);
  std::uniform_real_distribution<double> far(-1.0, 1.0);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 2000; ++i)
    points.emplace_back(sheet(rng), sheet(rng), 0.5);
  for (int i = 0; i < 100; ++i)
    points.push_back(points[i]);  // duplicates: distance 0 is not a spacing
  for (int i = 0; i < 250; ++i)
    points.emplace_back(far(rng), far(rng), 0.5 + far(rng));
  constexpr int kProbes = 200;
  for (const double quantile : {0.0, 0.5, 0.95, 1.0})
  {
    std::mt19937_64 spacing_rng(11);
    const double spacing_m = brick_pose::registration::neighbourSpacing(points, quantile, spacing_rng, kProbes);
    EXPECT_NEAR(spacing_m, spacingByScan(points, quantile, 11, kProbes), 1e-12) << "quantile " << quantile;
  }
}
