#include "brick_pose/registration/point_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
namespace
{
constexpr std::int64_t kAxisMask = (std::int64_t(1) << 21) - 1;

/// Fibonacci hashing: the *high* bits of key * 2^64 / phi. The low bits of
/// the product depend only on the low bits of the key, which hold the z cell
/// alone, so masking them sent every cell of a level face (one z) to the same
/// run of slots and made a lookup, hit or miss, walk that whole run.
std::uint64_t hashKey(std::uint64_t key, int shift) { return (key * 0x9E3779B97F4A7C15ull) >> shift; }

/// Cell index of a scaled coordinate; clamped so that absurd coordinates
/// cannot overflow the conversion (wrapping cells only cost extra checks).
std::int64_t cellIndex(double scaled)
{
  constexpr double kLimit = 4.0e15;
  return static_cast<std::int64_t>(std::floor(std::clamp(scaled, -kLimit, kLimit)));
}
}  // namespace

// Coordinates wrap at 2^21 cells per axis; a wrapped collision only adds
// points that the exact distance test then rejects.
std::uint64_t PointGrid::packKey(std::int64_t x, std::int64_t y, std::int64_t z)
{
  return (static_cast<std::uint64_t>(x & kAxisMask) << 42) | (static_cast<std::uint64_t>(y & kAxisMask) << 21) |
         static_cast<std::uint64_t>(z & kAxisMask);
}

PointGrid::PointGrid(const std::vector<Eigen::Vector3d>& points, double max_radius_m)
  : points_(&points), cell_size_m_(2.0 * max_radius_m)
{
  if (!(max_radius_m > 0.0) || !std::isfinite(max_radius_m))
    throw ConfigError("PointGrid: max_radius_m must be positive and finite, got " + std::to_string(max_radius_m));
  inv_cell_size_ = 1.0 / cell_size_m_;
  if (points.empty())
    return;

  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const Eigen::Vector3d scaled = points[i] * inv_cell_size_;
    keyed[i] = {packKey(cellIndex(scaled.x()), cellIndex(scaled.y()), cellIndex(scaled.z())),
                static_cast<std::uint32_t>(i)};
  }
  std::sort(keyed.begin(), keyed.end());

  std::size_t cell_count = 0;
  for (std::size_t i = 0; i < keyed.size(); ++i)
    cell_count += (i == 0 || keyed[i].first != keyed[i - 1].first) ? 1 : 0;
  std::size_t capacity = 16;
  hash_shift_ = 60;
  while (capacity < 2 * cell_count)
  {
    capacity *= 2;
    --hash_shift_;
  }
  table_.assign(capacity, Slot());
  sorted_indices_.resize(keyed.size());

  const std::uint64_t mask = capacity - 1;
  for (std::size_t begin = 0; begin < keyed.size();)
  {
    std::size_t end = begin;
    while (end < keyed.size() && keyed[end].first == keyed[begin].first)
    {
      sorted_indices_[end] = keyed[end].second;
      ++end;
    }
    std::uint64_t slot = hashKey(keyed[begin].first, hash_shift_) & mask;
    while (table_[slot].key != kEmptyKey)
      slot = (slot + 1) & mask;
    table_[slot] = {keyed[begin].first, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(end)};
    begin = end;
  }
}

const PointGrid::Slot* PointGrid::findCell(std::uint64_t key) const
{
  const std::uint64_t mask = table_.size() - 1;
  for (std::uint64_t slot = hashKey(key, hash_shift_) & mask;; slot = (slot + 1) & mask)
  {
    const Slot& candidate = table_[slot];
    if (candidate.key == key)
      return &candidate;
    if (candidate.key == kEmptyKey)
      return nullptr;
  }
}

void PointGrid::blockAround(const Eigen::Vector3d& query, std::uint64_t keys[8]) const
{
  std::int64_t low[3];
  for (int axis = 0; axis < 3; ++axis)
  {
    const double scaled = query[axis] * inv_cell_size_;
    // The query ball (radius <= half a cell) reaches the lower neighbour only
    // when the query sits in the lower half of its cell, the upper otherwise.
    low[axis] = cellIndex(scaled) - (scaled - std::floor(scaled) < 0.5 ? 1 : 0);
  }
  int k = 0;
  for (int dx = 0; dx < 2; ++dx)
    for (int dy = 0; dy < 2; ++dy)
      for (int dz = 0; dz < 2; ++dz)
        keys[k++] = packKey(low[0] + dx, low[1] + dy, low[2] + dz);
}

int PointGrid::nearestWithin(const Eigen::Vector3d& query, double radius_m) const
{
  int nearest = -1;
  double nearest_sq = std::numeric_limits<double>::infinity();
  forEachWithin(query, radius_m, [&](int index) {
    const double d_sq = ((*points_)[index] - query).squaredNorm();
    if (d_sq < nearest_sq)
    {
      nearest_sq = d_sq;
      nearest = index;
    }
  });
  return nearest;
}

bool PointGrid::anyWithin(const Eigen::Vector3d& query, double radius_m) const
{
  if (table_.empty())
    return false;
  const double radius_sq = radius_m * radius_m;
  std::uint64_t keys[8];
  blockAround(query, keys);
  for (std::uint64_t key : keys)
  {
    const Slot* cell = findCell(key);
    if (!cell)
      continue;
    for (std::uint32_t k = cell->begin; k < cell->end; ++k)
      if (((*points_)[sorted_indices_[k]] - query).squaredNorm() <= radius_sq)
        return true;
  }
  return false;
}
}  // namespace registration
}  // namespace brick_pose
