#include "brick_pose/segmentation/cell_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/core/utility.hpp>

namespace brick_pose
{
PixelRays::PixelRays(const PinholeCamera& camera)
{
  x_over_z.resize(static_cast<std::size_t>(std::max(0, camera.width_px)));
  y_over_z.resize(static_cast<std::size_t>(std::max(0, camera.height_px)));
  for (std::size_t u = 0; u < x_over_z.size(); ++u)
    x_over_z[u] = (static_cast<double>(u) - camera.cx_px) / camera.fx_px;
  for (std::size_t v = 0; v < y_over_z.size(); ++v)
    y_over_z[v] = (static_cast<double>(v) - camera.cy_px) / camera.fy_px;
}

CellGrid::CellGrid(const RgbdFrame& frame, const PixelRays& rays, int cell_px, const cv::Mat& excluded, bool parallel)
  : cell_px_(std::max(1, cell_px)),
    cols_((frame.width_px() + cell_px_ - 1) / cell_px_),
    rows_((frame.height_px() + cell_px_ - 1) / cell_px_),
    width_px_(frame.width_px()),
    height_px_(frame.height_px()),
    fx_px_(frame.camera.fx_px),
    fy_px_(frame.camera.fy_px),
    moments_(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_)),
    max_step_u_m_(moments_.size(), 0.0f),
    max_step_v_m_(moments_.size(), 0.0f)
{
  const bool has_excluded = !excluded.empty();
  // One band of cell rows per task; every cell is written by one task only.
  auto usable = [&](const float* depth, const std::uint8_t* skip, int u) {
    const float z = depth[u];
    return z > 0.0f && !(skip && skip[u]);  // false for NaN (no depth)
  };
  auto accumulateRows = [&](const cv::Range& cell_rows) {
    for (int row = cell_rows.start; row < cell_rows.end; ++row)
    {
      const std::size_t first_cell = static_cast<std::size_t>(row) * cols_;
      PlaneMoments* row_cells = &moments_[first_cell];
      float* row_step_u = &max_step_u_m_[first_cell];
      float* row_step_v = &max_step_v_m_[first_cell];
      const int v_begin = row * cell_px_, v_end = std::min(height_px_, (row + 1) * cell_px_);
      for (int v = v_begin; v < v_end; ++v)
      {
        const float* depth = frame.depth_m.ptr<float>(v);
        const std::uint8_t* skip = has_excluded ? excluded.ptr<std::uint8_t>(v) : nullptr;
        // The row above within the same cell, for the vertical steps.
        const float* depth_up = v > v_begin ? frame.depth_m.ptr<float>(v - 1) : nullptr;
        const std::uint8_t* skip_up = depth_up && has_excluded ? excluded.ptr<std::uint8_t>(v - 1) : nullptr;
        const double y_over_z = rays.y_over_z[v];
        for (int col = 0; col < cols_; ++col)
        {
          PlaneMoments& cell = row_cells[col];
          float step_u = row_step_u[col], step_v = row_step_v[col];
          const int u_begin = col * cell_px_, u_end = std::min(width_px_, (col + 1) * cell_px_);
          for (int u = u_begin; u < u_end; ++u)
          {
            if (!usable(depth, skip, u)) continue;
            const double z = depth[u];
            cell.add(rays.x_over_z[u] * z, y_over_z * z, z);
            if (u > u_begin && usable(depth, skip, u - 1)) step_u = std::max(step_u, std::abs(depth[u] - depth[u - 1]));
            if (depth_up && usable(depth_up, skip_up, u)) step_v = std::max(step_v, std::abs(depth[u] - depth_up[u]));
          }
          row_step_u[col] = step_u;
          row_step_v[col] = step_v;
        }
      }
    }
  };
  if (parallel)
    cv::parallel_for_(cv::Range(0, rows_), accumulateRows);
  else
    accumulateRows(cv::Range(0, rows_));
}

cv::Rect CellGrid::rect(int index) const
{
  const int col = index % cols_, row = index / cols_;
  const int u = col * cell_px_, v = row * cell_px_;
  return {u, v, std::min(cell_px_, width_px_ - u), std::min(cell_px_, height_px_ - v)};
}
}  // namespace brick_pose
