#include "brick_pose/registration/point_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
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
    keyed[i] = {packKey(grid_detail::cellIndex(scaled.x()), grid_detail::cellIndex(scaled.y()),
                        grid_detail::cellIndex(scaled.z())),
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
    std::uint64_t slot = grid_detail::hashKey(keyed[begin].first, hash_shift_) & mask;
    while (table_[slot].key != kEmptyKey)
      slot = (slot + 1) & mask;
    table_[slot] = {keyed[begin].first, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(end)};
    begin = end;
  }
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
