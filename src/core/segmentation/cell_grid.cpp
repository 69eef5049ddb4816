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
  // x = (x/z) z and y = (y/z) z, so every moment is a row constant times
  // one of seven sums over the row's pixels in a cell: n, z, z^2, a z,
  // a z^2, a^2 z^2, z^4 (a = x/z of the column; y/z is the row's constant).
  std::vector<double> a_squared(rays.x_over_z.size());
  for (std::size_t u = 0; u < a_squared.size(); ++u) a_squared[u] = rays.x_over_z[u] * rays.x_over_z[u];
  auto accumulateRows = [&](const cv::Range& cell_rows) {
    std::vector<float> row_depth(static_cast<std::size_t>(width_px_));
    std::vector<float> above_depth(static_cast<std::size_t>(width_px_));
    for (int row = cell_rows.start; row < cell_rows.end; ++row)
    {
      const std::size_t first_cell = static_cast<std::size_t>(row) * cols_;
      const int v_begin = row * cell_px_, v_end = std::min(height_px_, (row + 1) * cell_px_);
      for (int v = v_begin; v < v_end; ++v)
      {
        // The row's usable depths, 0 where there is none (NaN) or it is excluded.
        const float* depth = frame.depth_m.ptr<float>(v);
        const std::uint8_t* skip = has_excluded ? excluded.ptr<std::uint8_t>(v) : nullptr;
        for (int u = 0; u < width_px_; ++u)
        {
          const float z = depth[u];
          row_depth[u] = (z > 0.0f && !(skip && skip[u])) ? z : 0.0f;
        }
        const double b = rays.y_over_z[v];
        const bool has_above = v > v_begin;
        for (int col = 0; col < cols_; ++col)
        {
          const int u_begin = col * cell_px_, u_end = std::min(width_px_, (col + 1) * cell_px_);
          double n = 0.0, sz = 0.0, sz2 = 0.0, saz = 0.0, saz2 = 0.0, sa2z2 = 0.0, sz4 = 0.0;
          float step_u = 0.0f, step_v = 0.0f;
          for (int u = u_begin; u < u_end; ++u)
          {
            const float zf = row_depth[u];
            const double z = zf, z2 = z * z, a = rays.x_over_z[u];
            n += zf > 0.0f ? 1.0 : 0.0;
            sz += z;
            sz2 += z2;
            saz += a * z;
            saz2 += a * z2;
            sa2z2 += a_squared[u] * z2;
            sz4 += z2 * z2;
            if (u > u_begin && zf > 0.0f && row_depth[u - 1] > 0.0f) step_u = std::max(step_u, std::abs(zf - row_depth[u - 1]));
            if (has_above && zf > 0.0f && above_depth[u] > 0.0f) step_v = std::max(step_v, std::abs(zf - above_depth[u]));
          }
          PlaneMoments& cell = moments_[first_cell + col];
          cell.count += n;
          cell.sum += Eigen::Vector3d(saz, b * sz, sz);
          cell.xx += sa2z2;
          cell.xy += b * saz2;
          cell.xz += saz2;
          cell.yy += b * b * sz2;
          cell.yz += b * sz2;
          cell.zz += sz2;
          cell.z4 += sz4;
          max_step_u_m_[first_cell + col] = std::max(max_step_u_m_[first_cell + col], step_u);
          max_step_v_m_[first_cell + col] = std::max(max_step_v_m_[first_cell + col], step_v);
        }
        std::swap(row_depth, above_depth);
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
