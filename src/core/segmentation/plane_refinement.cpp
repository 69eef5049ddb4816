#include "brick_pose/segmentation/plane_refinement.h"

#include <cmath>
#include <cstdint>

#include <opencv2/core/utility.hpp>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
/// Plane n.p + d = 0 in single precision for the per-pixel distances.
struct PixelPlane
{
  float nx, ny, nz, d;
};

/// Everything the per-pixel tests need, built once per frame.
class PixelTester
{
public:
  PixelTester(const RgbdFrame& frame, const PixelRays& rays, const CellPlanes& cell_planes, const DepthNoise& noise,
              const cv::Mat& excluded, const PlaneRefinementParams& params)
    : frame_(frame), excluded_(excluded), noise_(noise), params_(params)
  {
    planes_.reserve(cell_planes.planes.size());
    for (const MomentPlane& plane : cell_planes.planes)
      planes_.push_back({static_cast<float>(plane.normal.x()), static_cast<float>(plane.normal.y()),
                         static_cast<float>(plane.normal.z()), static_cast<float>(-plane.normal.dot(plane.centroid_m))});
    x_over_z_.assign(rays.x_over_z.begin(), rays.x_over_z.end());
    y_over_z_.assign(rays.y_over_z.begin(), rays.y_over_z.end());
  }

  /// Depth usable for a plane (NaN when there is none or it is excluded).
  float depth(int u, int v) const
  {
    const float z = frame_.depth_m.ptr<float>(v)[u];
    if (!(z > 0.0f) || (!excluded_.empty() && excluded_.ptr<std::uint8_t>(v)[u])) return NAN;
    return z;
  }

  float distance(int plane, int u, int v, float z) const
  {
    const PixelPlane& p = planes_[plane];
    return std::abs(p.nx * x_over_z_[u] * z + p.ny * y_over_z_[v] * z + p.nz * z + p.d);
  }

  float tolerance(float z) const
  {
    return static_cast<float>(params_.pixel_sigma_factor * noise_.sigma(z) + params_.pixel_floor_m);
  }

private:
  const RgbdFrame& frame_;
  const cv::Mat& excluded_;
  const DepthNoise& noise_;
  const PlaneRefinementParams& params_;
  std::vector<PixelPlane> planes_;
  std::vector<float> x_over_z_, y_over_z_;
};
}  // namespace

void PlaneRefinementParams::validate() const
{
  if (!(pixel_sigma_factor > 0.0)) throw ConfigError("colour-free segmenter: pixel_sigma_factor must be > 0");
  if (!(pixel_floor_m >= 0.0)) throw ConfigError("colour-free segmenter: pixel_floor_m must be >= 0");
}

cv::Mat refinePlaneLabels(const RgbdFrame& frame, const PixelRays& rays, const CellGrid& grid,
                          const CellPlanes& cell_planes, const DepthNoise& noise, const cv::Mat& excluded,
                          const PlaneRefinementParams& params, bool parallel)
{
  const int width = frame.width_px(), height = frame.height_px();
  cv::Mat labels(height, width, CV_32SC1, cv::Scalar(-1));
  if (cell_planes.planes.empty()) return labels;
  const int cols = grid.cols(), rows = grid.rows(), cell_px = grid.cellPx();
  const std::vector<int>& cell_labels = cell_planes.cell_labels;

  // Inner cells: labelled, with all eight neighbours in the same plane.
  std::vector<std::uint8_t> inner(static_cast<std::size_t>(grid.size()), 0);
  std::vector<std::uint8_t> plane_has_inner(cell_planes.planes.size(), 0);
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col)
    {
      const int label = cell_labels[row * cols + col];
      if (label < 0) continue;
      bool surrounded = true;
      for (int dr = -1; dr <= 1 && surrounded; ++dr)
        for (int dc = -1; dc <= 1 && surrounded; ++dc)
        {
          const int r = row + dr, c = col + dc;
          if (r >= 0 && c >= 0 && r < rows && c < cols && cell_labels[r * cols + c] != label) surrounded = false;
        }
      inner[row * cols + col] = surrounded ? 1 : 0;
      if (surrounded) plane_has_inner[label] = 1;
    }
  // Seed cells: the inner ones; a plane too small to have any seeds from
  // all its cells (and those pixels stay open to its neighbours).
  auto isSeedCell = [&](int cell) {
    const int label = cell_labels[cell];
    return label >= 0 && (inner[cell] || !plane_has_inner[label]);
  };

  const PixelTester tester(frame, rays, cell_planes, noise, excluded, params);
  auto labelSeedRows = [&](const cv::Range& cell_rows) {
    for (int row = cell_rows.start; row < cell_rows.end; ++row)
      for (int col = 0; col < cols; ++col)
      {
        const int cell = row * cols + col;
        if (!isSeedCell(cell)) continue;
        const int label = cell_labels[cell];
        const cv::Rect box = grid.rect(cell);
        for (int v = box.y; v < box.y + box.height; ++v)
        {
          int* label_row = labels.ptr<int>(v);
          for (int u = box.x; u < box.x + box.width; ++u)
          {
            const float z = tester.depth(u, v);
            if (!std::isnan(z) && tester.distance(label, u, v, z) <= tester.tolerance(z)) label_row[u] = label;
          }
        }
      }
  };
  if (parallel)
    cv::parallel_for_(cv::Range(0, rows), labelSeedRows);
  else
    labelSeedRows(cv::Range(0, rows));

  // Growth from the seed cells that touch an undecided cell.
  std::vector<int> queue;
  for (int cell = 0; cell < grid.size(); ++cell)
  {
    if (!isSeedCell(cell)) continue;
    const int col = cell % cols, row = cell / cols;
    bool touches_open = !inner[cell];
    for (int dr = -1; dr <= 1 && !touches_open; ++dr)
      for (int dc = -1; dc <= 1 && !touches_open; ++dc)
      {
        const int r = row + dr, c = col + dc;
        if (r >= 0 && c >= 0 && r < rows && c < cols && !inner[r * cols + c]) touches_open = true;
      }
    if (!touches_open) continue;
    const cv::Rect box = grid.rect(cell);
    for (int v = box.y; v < box.y + box.height; ++v)
    {
      const int* label_row = labels.ptr<int>(v);
      for (int u = box.x; u < box.x + box.width; ++u)
        if (label_row[u] >= 0) queue.push_back(v * width + u);
    }
  }

  int* label_data = labels.ptr<int>(0);
  auto locked = [&](int u, int v) { return inner[(v / cell_px) * cols + u / cell_px] != 0; };
  for (std::size_t head = 0; head < queue.size(); ++head)
  {
    const int pixel = queue[head];
    const int label = label_data[pixel];
    const int u = pixel % width, v = pixel / width;
    const int neighbours[4][2] = {{u - 1, v}, {u + 1, v}, {u, v - 1}, {u, v + 1}};
    for (const auto& [nu, nv] : neighbours)
    {
      if (nu < 0 || nv < 0 || nu >= width || nv >= height || locked(nu, nv)) continue;
      const int next = nv * width + nu;
      const int current = label_data[next];
      if (current == label) continue;
      const float z = tester.depth(nu, nv);
      if (std::isnan(z)) continue;
      const float distance = tester.distance(label, nu, nv, z);
      if (distance > tester.tolerance(z)) continue;
      if (current >= 0 && distance >= tester.distance(current, nu, nv, z)) continue;
      label_data[next] = label;
      queue.push_back(next);
    }
  }
  return labels;
}
}  // namespace brick_pose
