#include "brick_pose/registration/shell_pair_index.h"

#include <algorithm>
#include <cmath>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
namespace
{
constexpr int kBitsPerAxis = 21;
constexpr int kLeafSize = 8;

std::uint64_t spreadBits(std::uint64_t v)
{
  v &= 0x1FFFFF;
  v = (v | v << 32) & 0x1F00000000FFFFull;
  v = (v | v << 16) & 0x1F0000FF0000FFull;
  v = (v | v << 8) & 0x100F00F00F00F00Full;
  v = (v | v << 4) & 0x10C30C30C30C30C3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

std::uint64_t mortonCode(std::uint64_t x, std::uint64_t y, std::uint64_t z)
{
  return spreadBits(x) << 2 | spreadBits(y) << 1 | spreadBits(z);
}

// Squared distance bounds between any point of box a and any point of box b.
void boxDistanceBoundsSq(const Eigen::Vector3d& a_min, const Eigen::Vector3d& a_max, const Eigen::Vector3d& b_min,
                         const Eigen::Vector3d& b_max, double& min_sq, double& max_sq)
{
  min_sq = 0.0;
  max_sq = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    const double gap = std::max({0.0, a_min[axis] - b_max[axis], b_min[axis] - a_max[axis]});
    const double span = std::max(a_max[axis] - b_min[axis], b_max[axis] - a_min[axis]);
    min_sq += gap * gap;
    max_sq += span * span;
  }
}
}  // namespace

struct ShellPairIndex::ShellQuery
{
  double inner_sq;
  double outer_sq;
  std::vector<std::pair<int, int>> pairs;
};

ShellPairIndex::ShellPairIndex(const std::vector<Eigen::Vector3d>& points, double finest_cell_m) : points_(points)
{
  if (!(finest_cell_m > 0.0) || !std::isfinite(finest_cell_m))
    throw ConfigError("ShellPairIndex: finest_cell_m must be positive and finite, got " +
                      std::to_string(finest_cell_m));
  if (points.empty())
    return;

  Eigen::Vector3d lower = points.front();
  Eigen::Vector3d upper = points.front();
  for (const Eigen::Vector3d& p : points)
  {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  // Coarsen the finest cells if the cloud would not fit in 2^21 of them.
  const double max_cells = static_cast<double>((1u << kBitsPerAxis) - 1);
  const double cell_m = std::max(finest_cell_m, (upper - lower).maxCoeff() / max_cells);

  std::vector<std::pair<std::uint64_t, int>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    // Clamped to [0, max_cells] with NaN sent to 0: the conversion to an
    // unsigned integer is undefined outside its range.
    const Eigen::Vector3d cell = ((points[i] - lower) / cell_m).unaryExpr([max_cells](double x) {
      return std::isnan(x) ? 0.0 : std::clamp(std::floor(x), 0.0, max_cells);
    });
    keyed[i] = {mortonCode(static_cast<std::uint64_t>(cell.x()), static_cast<std::uint64_t>(cell.y()),
                           static_cast<std::uint64_t>(cell.z())),
                static_cast<int>(i)};
  }
  std::sort(keyed.begin(), keyed.end());
  order_.resize(keyed.size());
  codes_.resize(keyed.size());
  sorted_points_.resize(keyed.size());
  for (std::size_t k = 0; k < keyed.size(); ++k)
  {
    codes_[k] = keyed[k].first;
    order_[k] = keyed[k].second;
    sorted_points_[k] = points[keyed[k].second];
  }
  nodes_.reserve(2 * points.size() / kLeafSize + 16);
  nodes_.emplace_back();
  buildNode(0, 0, static_cast<int>(points.size()), kBitsPerAxis);
}

// A node holds the points whose Morton codes agree above 3 * level bits, i.e.
// one cell of size cell * 2^level. Its children are the occupied sub-cells;
// levels with a single occupied sub-cell are skipped.
void ShellPairIndex::buildNode(int node, int begin, int end, int level)
{
  Eigen::Vector3d box_min = points_[order_[begin]];
  Eigen::Vector3d box_max = box_min;
  for (int k = begin + 1; k < end; ++k)
  {
    box_min = box_min.cwiseMin(points_[order_[k]]);
    box_max = box_max.cwiseMax(points_[order_[k]]);
  }
  nodes_[node].box_min = box_min;
  nodes_[node].box_max = box_max;
  nodes_[node].begin = begin;
  nodes_[node].end = end;
  if (end - begin <= kLeafSize)
    return;

  std::vector<int> splits;
  for (; level > 0 && splits.empty(); --level)
  {
    const int shift = 3 * (level - 1);
    for (int k = begin + 1; k < end; ++k)
      if ((codes_[k] >> shift) != (codes_[k - 1] >> shift))
        splits.push_back(k);
  }
  if (splits.empty())
    return;  // all points in one finest cell: a (large) leaf

  const int first_child = static_cast<int>(nodes_.size());
  const int child_count = static_cast<int>(splits.size()) + 1;
  nodes_[node].first_child = first_child;
  nodes_[node].child_count = child_count;
  nodes_.resize(nodes_.size() + child_count);
  int child_begin = begin;
  for (int c = 0; c < child_count; ++c)
  {
    const int child_end = c < child_count - 1 ? splits[c] : end;
    buildNode(first_child + c, child_begin, child_end, level);
    child_begin = child_end;
  }
}

std::vector<std::pair<int, int>> ShellPairIndex::pairsInShell(double radius_m, double tolerance_m) const
{
  if (!(radius_m >= 0.0) || !(tolerance_m >= 0.0))
    throw ConfigError("ShellPairIndex: radius and tolerance must be non-negative");
  ShellQuery query;
  const double inner = std::max(0.0, radius_m - tolerance_m);
  query.inner_sq = inner * inner;
  query.outer_sq = (radius_m + tolerance_m) * (radius_m + tolerance_m);
  if (!nodes_.empty())
    visit(0, 0, query);
  return std::move(query.pairs);
}

// Visits the cell pair (a, b): dropped when the shell cannot pass between
// them, tested point by point once small or entirely inside the shell,
// otherwise refined by splitting the larger cell.
void ShellPairIndex::visit(int a, int b, ShellQuery& query) const
{
  const Node& node_a = nodes_[a];
  const Node& node_b = nodes_[b];
  double min_sq = 0.0;
  double max_sq = 0.0;
  boxDistanceBoundsSq(node_a.box_min, node_a.box_max, node_b.box_min, node_b.box_max, min_sq, max_sq);
  if (min_sq > query.outer_sq || max_sq < query.inner_sq)
    return;
  const bool inside_shell = min_sq >= query.inner_sq && max_sq <= query.outer_sq;

  if (a == b)
  {
    if (node_a.isLeaf() || inside_shell)
    {
      testAllPairs(node_a, node_a, true, query);
      return;
    }
    for (int i = 0; i < node_a.child_count; ++i)
      for (int j = i; j < node_a.child_count; ++j)
        visit(node_a.first_child + i, node_a.first_child + j, query);
    return;
  }
  if (inside_shell || (node_a.isLeaf() && node_b.isLeaf()))
  {
    testAllPairs(node_a, node_b, false, query);
    return;
  }
  const bool split_a = !node_a.isLeaf() && (node_b.isLeaf() || node_a.end - node_a.begin >= node_b.end - node_b.begin);
  if (split_a)
    for (int i = 0; i < node_a.child_count; ++i)
      visit(node_a.first_child + i, b, query);
  else
    for (int j = 0; j < node_b.child_count; ++j)
      visit(a, node_b.first_child + j, query);
}

void ShellPairIndex::testAllPairs(const Node& a, const Node& b, bool same, ShellQuery& query) const
{
  for (int k = a.begin; k < a.end; ++k)
  {
    const Eigen::Vector3d& p = sorted_points_[k];
    for (int m = same ? k + 1 : b.begin; m < b.end; ++m)
    {
      const double d_sq = (sorted_points_[m] - p).squaredNorm();
      if (d_sq >= query.inner_sq && d_sq <= query.outer_sq)
        query.pairs.emplace_back(std::min(order_[k], order_[m]), std::max(order_[k], order_[m]));
    }
  }
}

std::vector<std::pair<int, int>> bruteForcePairsInShell(const std::vector<Eigen::Vector3d>& points, double radius_m,
                                                        double tolerance_m)
{
  const double inner = std::max(0.0, radius_m - tolerance_m);
  const double inner_sq = inner * inner;
  const double outer_sq = (radius_m + tolerance_m) * (radius_m + tolerance_m);
  std::vector<std::pair<int, int>> pairs;
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j)
    {
      const double d_sq = (points[j] - points[i]).squaredNorm();
      if (d_sq >= inner_sq && d_sq <= outer_sq)
        pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
    }
  return pairs;
}
}  // namespace registration
}  // namespace brick_pose
