#pragma once
// A hashed regular grid over a point set for fixed-radius neighbour queries.
// The cell size is twice the largest radius a query may use, so that a query
// only ever looks at the 2x2x2 block of cells around its point.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace brick_pose
{
namespace registration
{
class PointGrid
{
public:
  PointGrid() = default;
  /// `points` must outlive the grid; queries may use radii up to
  /// max_radius_m. Throws ConfigError if max_radius_m <= 0.
  PointGrid(const std::vector<Eigen::Vector3d>& points, double max_radius_m);

  double maxRadius() const { return 0.5 * cell_size_m_; }

  /// Rebuilds the grid for queries up to radius_m once its cells have grown
  /// too coarse for them: a narrow query in a coarse cell scans many points.
  /// Iterative fits call it as their match radius shrinks.
  void shrinkTo(double radius_m)
  {
    if (points_ && radius_m < kRebuildBelowFraction * maxRadius()) *this = PointGrid(*points_, radius_m);
  }

  /// Index of the nearest point within radius_m (<= maxRadius()) of `query`,
  /// or -1 when there is none.
  int nearestWithin(const Eigen::Vector3d& query, double radius_m) const;

  /// True when some point lies within radius_m (<= maxRadius()) of `query`;
  /// cheaper than nearestWithin() because it stops at the first hit.
  bool anyWithin(const Eigen::Vector3d& query, double radius_m) const;

  /// Calls visit(index) for every point within radius_m (<= maxRadius()).
  template <typename Visitor>
  void forEachWithin(const Eigen::Vector3d& query, double radius_m, Visitor&& visit) const;

private:
  struct Slot
  {
    std::uint64_t key = kEmptyKey;
    std::uint32_t begin = 0;
    std::uint32_t end = 0;
  };
  static constexpr std::uint64_t kEmptyKey = ~std::uint64_t(0);
  static constexpr double kRebuildBelowFraction = 0.7;

  static std::uint64_t packKey(std::int64_t x, std::int64_t y, std::int64_t z);
  const Slot* findCell(std::uint64_t key) const;
  /// The 8 cells that can hold points within maxRadius() of `query`.
  void blockAround(const Eigen::Vector3d& query, std::uint64_t keys[8]) const;

  const std::vector<Eigen::Vector3d>* points_ = nullptr;
  double cell_size_m_ = 0.0;
  double inv_cell_size_ = 0.0;
  std::vector<Slot> table_;  // open addressing, power-of-two size
  int hash_shift_ = 60;  // 64 - log2(table_.size())
  std::vector<std::uint32_t> sorted_indices_;
};

template <typename Visitor>
void PointGrid::forEachWithin(const Eigen::Vector3d& query, double radius_m, Visitor&& visit) const
{
  if (table_.empty())
    return;
  const double radius_sq = radius_m * radius_m;
  std::uint64_t keys[8];
  blockAround(query, keys);
  for (std::uint64_t key : keys)
  {
    const Slot* cell = findCell(key);
    if (!cell)
      continue;
    for (std::uint32_t k = cell->begin; k < cell->end; ++k)
    {
      const std::uint32_t index = sorted_indices_[k];
      if (((*points_)[index] - query).squaredNorm() <= radius_sq)
        visit(static_cast<int>(index));
    }
  }
}
}  // namespace registration
}  // namespace brick_pose
