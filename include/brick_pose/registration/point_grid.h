#pragma once
// A hashed regular grid over a point set for fixed-radius neighbour queries.
// The cell size is twice the largest radius a query may use, so that a query
// only ever looks at the 2x2x2 block of cells around its point.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace brick_pose
{
namespace registration
{
// In the header so that the queries, which the registration runs millions of
// times per view, inline them (out of line they cost a call per cell).
namespace grid_detail
{
constexpr std::int64_t kAxisMask = (std::int64_t(1) << 21) - 1;

/// Fibonacci hashing: the *high* bits of key * 2^64 / phi. The low bits of
/// the product depend only on the low bits of the key, which hold the z cell
/// alone, so masking them sent every cell of a level face (one z) to the same
/// run of slots and made a lookup, hit or miss, walk that whole run.
inline std::uint64_t hashKey(std::uint64_t key, int shift) { return (key * 0x9E3779B97F4A7C15ull) >> shift; }

/// Cell index of a scaled coordinate; clamped so that absurd coordinates
/// cannot overflow the conversion (wrapping cells only cost extra checks).
inline std::int64_t cellIndex(double scaled)
{
  constexpr double kLimit = 4.0e15;
  // A NaN query (a degenerate pose applied to a point) matches nothing: any
  // cell will do, and converting NaN to an integer is undefined.
  if (std::isnan(scaled))
    return 0;
  return static_cast<std::int64_t>(std::floor(std::clamp(scaled, -kLimit, kLimit)));
}
}  // namespace grid_detail

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

// Coordinates wrap at 2^21 cells per axis; a wrapped collision only adds
// points that the exact distance test then rejects.
inline std::uint64_t PointGrid::packKey(std::int64_t x, std::int64_t y, std::int64_t z)
{
  return (static_cast<std::uint64_t>(x & grid_detail::kAxisMask) << 42) |
         (static_cast<std::uint64_t>(y & grid_detail::kAxisMask) << 21) |
         static_cast<std::uint64_t>(z & grid_detail::kAxisMask);
}

inline const PointGrid::Slot* PointGrid::findCell(std::uint64_t key) const
{
  const std::uint64_t mask = table_.size() - 1;
  for (std::uint64_t slot = grid_detail::hashKey(key, hash_shift_) & mask;; slot = (slot + 1) & mask)
  {
    const Slot& candidate = table_[slot];
    if (candidate.key == key)
      return &candidate;
    if (candidate.key == kEmptyKey)
      return nullptr;
  }
}

inline void PointGrid::blockAround(const Eigen::Vector3d& query, std::uint64_t keys[8]) const
{
  std::int64_t low[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    const double scaled = query[axis] * inv_cell_size_;
    // The query ball (radius <= half a cell) reaches the lower neighbour only
    // when the query sits in the lower half of its cell, the upper otherwise.
    low[axis] = grid_detail::cellIndex(scaled) - (scaled - std::floor(scaled) < 0.5 ? 1 : 0);
  }
  int k = 0;
  for (int dx = 0; dx < 2; ++dx)
    for (int dy = 0; dy < 2; ++dy)
      for (int dz = 0; dz < 2; ++dz)
        keys[k++] = packKey(low[0] + dx, low[1] + dy, low[2] + dz);
}

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
