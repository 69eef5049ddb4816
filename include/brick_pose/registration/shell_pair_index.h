#pragma once
// The "smart index" of Super 4PCS (Mellado, Aiger, Mitra, SGP 2014, sec. 4):
// all pairs of points whose distance lies in [r - tolerance, r + tolerance],
// found without testing all pairs.
//
// Points are hashed into a regular grid whose finest cells are about the
// tolerance wide; the grid is organised as an octree of cells of size
// cell * 2^k (Morton order, cells merged upwards). A query rasterises the
// sphere shell of radius r +- tolerance around each cell coarse-to-fine: a
// pair of cells is subdivided only while the shell passes through it and is
// dropped as soon as the shell misses it, so the work is proportional to the
// number of cells the shell crosses plus the number of pairs reported,
// instead of quadratic in the number of points.

#include <cstdint>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace brick_pose
{
namespace registration
{
class ShellPairIndex
{
public:
  /// `points` must outlive the index. finest_cell_m > 0 (ConfigError).
  ShellPairIndex(const std::vector<Eigen::Vector3d>& points, double finest_cell_m);

  /// Unordered pairs (i < j) with r - tolerance <= |p_i - p_j| <= r + tolerance.
  std::vector<std::pair<int, int>> pairsInShell(double radius_m, double tolerance_m) const;

  std::size_t nodeCount() const { return nodes_.size(); }

private:
  struct Node
  {
    Eigen::Vector3d box_min;
    Eigen::Vector3d box_max;
    int begin = 0;  // range in order_
    int end = 0;
    int first_child = -1;  // children are consecutive nodes
    int child_count = 0;
    bool isLeaf() const { return child_count == 0; }
  };
  struct ShellQuery;

  /// Fills nodes_[node] for order_[begin, end) whose codes share all bits above `level`.
  void buildNode(int node, int begin, int end, int level);
  void visit(int a, int b, ShellQuery& query) const;
  void testAllPairs(const Node& a, const Node& b, bool same, ShellQuery& query) const;

  const std::vector<Eigen::Vector3d>& points_;
  std::vector<int> order_;  // point indices in Morton order
  std::vector<std::uint64_t> codes_;  // Morton code of order_[k]
  // points_[order_[k]]: the pair tests walk cells in Morton order, and a copy
  // in that order reads memory in sequence rather than all over the cloud.
  std::vector<Eigen::Vector3d> sorted_points_;
  std::vector<Node> nodes_;
};

/// The reference answer: all pairs tested. For tests and tiny clouds only.
std::vector<std::pair<int, int>> bruteForcePairsInShell(const std::vector<Eigen::Vector3d>& points,
                                                        double radius_m, double tolerance_m);
}  // namespace registration
}  // namespace brick_pose
