#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <utility>

#include "brick_pose/registration/congruent_set_finder.h"

namespace brick_pose
{
namespace registration
{
namespace
{
double angleRad(const Eigen::Vector3d& u, const Eigen::Vector3d& v)
{
  return std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0));
}

/// The rule written out for one order: the pair (p, q) matches the base pair
/// when the angles between the normals and between each normal and the
/// segment p -> q are the base pair's within the tolerance.
bool matchesBase(const PointSet& cloud, int p, int q, const Eigen::Vector3d& base_p, const Eigen::Vector3d& base_q,
                 const Eigen::Vector3d& base_np, const Eigen::Vector3d& base_nq, double tolerance_rad)
{
  const Eigen::Vector3d segment = cloud.points[q] - cloud.points[p];
  const Eigen::Vector3d base_segment = base_q - base_p;
  return std::abs(angleRad(cloud.normals[p], cloud.normals[q]) - angleRad(base_np, base_nq)) <= tolerance_rad &&
         std::abs(angleRad(cloud.normals[p], segment) - angleRad(base_np, base_segment)) <= tolerance_rad &&
         std::abs(angleRad(cloud.normals[q], segment) - angleRad(base_nq, base_segment)) <= tolerance_rad;
}

PointSet randomCloudWithNormals(int count, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> coordinate(-0.1, 0.1);
  std::normal_distribution<double> gauss(0.0, 1.0);
  PointSet cloud;
  for (int i = 0; i < count; ++i)
  {
    cloud.points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
    // Not unit length: the finder must normalise them itself.
    cloud.normals.push_back(Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)) * (0.5 + 0.1 * (i % 7)));
  }
  return cloud;
}
}  // namespace

// orderedPairs decides both orders of a shell pair from one set of dot
// products (the reverse order negates the segment); the pairs it returns must
// be exactly those that pass the angle rule checked order by order.
TEST(CongruentSetFinder, OrderedPairsAreThoseWhoseNormalsMatchInThatOrder)
{
  std::mt19937_64 rng(7);
  const PointSet cloud = randomCloudWithNormals(300, rng);
  const ShellPairIndex index(cloud.points, 0.005);
  const CongruentSetFinder finder(cloud, index);
  const Eigen::Vector3d base_p(0.0, 0.0, 0.0);
  const Eigen::Vector3d base_q(0.08, 0.0, 0.0);
  // Asymmetric: the pair matches in one order and not, in general, the other.
  const Eigen::Vector3d base_np = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  const Eigen::Vector3d base_nq(0.0, 0.0, 1.0);
  CongruenceTolerances tolerances;
  tolerances.distance_m = 0.004;
  tolerances.normal_rad = 0.35;

  const auto found = finder.orderedPairs(0.08, base_p, base_q, base_np, base_nq, tolerances);
  const std::set<std::pair<int, int>> found_set(found.begin(), found.end());
  EXPECT_EQ(found_set.size(), found.size()) << "an ordered pair reported twice";

  std::set<std::pair<int, int>> expected;
  for (const auto& [i, j] : index.pairsInShell(0.08, tolerances.distance_m))
  {
    if (matchesBase(cloud, i, j, base_p, base_q, base_np, base_nq, tolerances.normal_rad))
      expected.emplace(i, j);
    if (matchesBase(cloud, j, i, base_p, base_q, base_np, base_nq, tolerances.normal_rad))
      expected.emplace(j, i);
  }
  ASSERT_GT(expected.size(), 5u) << "the case must exercise the rule";
  EXPECT_EQ(found_set, expected);
}
}  // namespace registration
}  // namespace brick_pose
