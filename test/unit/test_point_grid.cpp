#include <gtest/gtest.h>

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
