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
  for (int j = std::max(0, first_row); j < ny_; ++j)
  {
    int row = 0;
    for (int i = 0; i < nx_; ++i)
    {
      row += states[static_cast<std::size_t>(j) * nx_ + i] == state_ ? 1 : 0;
      sums_[static_cast<std::size_t>(j + 1) * (nx_ + 1) + i + 1] = at(i + 1, j) + row;
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
