#pragma once
// How many cells of a grid hold one state, over any rectangle, in constant
// time (a summed-area table). The face tiler asks this for every candidate
// tile and every line it snaps an edge to, thousands of times per segment;
// counting cell by cell made the tiling of a row of touching bricks cost
// more than everything else in the front end.

#include <cstdint>
#include <vector>

namespace brick_pose
{
class CellCounts
{
public:
  CellCounts() = default;
  /// `states`: nx * ny cells, row by row (cell (i, j) at j * nx + i).
  CellCounts(const std::vector<std::uint8_t>& states, int nx, int ny, std::uint8_t state);

  /// The counts again after cells of rows from `first_row` on changed (the
  /// grid's size unchanged): rows before it keep their sums.
  void update(const std::vector<std::uint8_t>& states, int first_row);

  /// Cells (i, j) with i in [i0, i1) and j in [j0, j1) holding the state;
  /// cells outside the grid count as not holding it.
  int count(int i0, int i1, int j0, int j1) const;

private:
  int at(int i, int j) const { return sums_[static_cast<std::size_t>(j) * (nx_ + 1) + i]; }

  int nx_ = 0, ny_ = 0;
  std::uint8_t state_ = 0;
  std::vector<int> sums_;  ///< (nx + 1) x (ny + 1): cells below and left of each corner
};
}  // namespace brick_pose
