#include "brick_pose/roi/cell_counts.h"

#include <algorithm>

namespace brick_pose
{
CellCounts::CellCounts(const std::vector<std::uint8_t>& states, int nx, int ny, std::uint8_t state)
  : nx_(nx), ny_(ny), state_(state), sums_(static_cast<std::size_t>(nx + 1) * (ny + 1), 0)
{
  update(states, 0);
}

void CellCounts::update(const std::vector<std::uint8_t>& states, int first_row)
{
  // Locals, so the stores to the sums need not reload the grid's size.
  const int nx = nx_, ny = ny_;
  const std::uint8_t state = state_;
  const std::size_t stride = static_cast<std::size_t>(nx) + 1;
  int* const sums = sums_.data();
  const std::uint8_t* const cells = states.data();
  for (int j = std::max(0, first_row); j < ny; ++j)
  {
    const int* const below = sums + static_cast<std::size_t>(j) * stride;
    int* const row_sums = sums + static_cast<std::size_t>(j + 1) * stride;
    const std::uint8_t* const row_cells = cells + static_cast<std::size_t>(j) * nx;
    int row = 0;
    for (int i = 0; i < nx; ++i)
    {
      row += row_cells[i] == state ? 1 : 0;
      row_sums[i + 1] = below[i + 1] + row;
    }
  }
}

int CellCounts::count(int i0, int i1, int j0, int j1) const
{
  i0 = std::max(i0, 0);
  j0 = std::max(j0, 0);
  i1 = std::min(i1, nx_);
  j1 = std::min(j1, ny_);
  if (i1 <= i0 || j1 <= j0) return 0;
  return at(i1, j1) - at(i0, j1) - at(i1, j0) + at(i0, j0);
}
}  // namespace brick_pose
