#include "brick_pose/segmentation/plane_refinement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/core/utility.hpp>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
/// Everything the per-pixel tests need, in single precision, built once per
/// frame: a pixel (u, v) with depth z is at distance
/// |z (nx x_u + ny y_v + nz) + d| from plane (n, d).
class PixelTester
{
public:
  PixelTester(const RgbdFrame& frame, const PixelRays& rays, const CellPlanes& cell_planes, const DepthNoise& noise,
              const cv::Mat& excluded, const PlaneRefinementParams& params)
    : frame_(frame),
      excluded_(excluded),
      has_excluded_(!excluded.empty()),
      x_over_z_(rays.x_over_z.begin(), rays.x_over_z.end()),
      y_over_z_(rays.y_over_z.begin(), rays.y_over_z.end()),
      sigma_at_1m_(static_cast<float>(noise.sigma_at_1m_m)),
      sigma_floor_(static_cast<float>(noise.floor_m)),
      sigma_factor_(static_cast<float>(params.pixel_sigma_factor)),
      floor_(static_cast<float>(params.pixel_floor_m))
  {
    planes_.reserve(cell_planes.planes.size());
    for (const MomentPlane& plane : cell_planes.planes)
      planes_.push_back({static_cast<float>(plane.normal.x()), static_cast<float>(plane.normal.y()),
                         static_cast<float>(plane.normal.z()), static_cast<float>(-plane.normal.dot(plane.centroid_m))});
  }

  /// Row v of the depth and of the excluded mask (null without one), read
  /// a row at a time by the loops over windows and cells.
  struct DepthRow
  {
    const float* depth_m;
    const std::uint8_t* excluded;
    /// Depth usable for a plane at column u: 0 when there is none or the
    /// pixel is excluded.
    float at(int u) const
    {
      const float z = depth_m[u];
      return (z > 0.0f && !(excluded && excluded[u])) ? z : 0.0f;
    }
  };
  DepthRow depthRow(int v) const
  {
    return {frame_.depth_m.ptr<float>(v), has_excluded_ ? excluded_.ptr<std::uint8_t>(v) : nullptr};
  }

  /// Depth usable for a plane: 0 when there is none or the pixel is excluded.
  float depth(int u, int v) const { return depthRow(v).at(u); }

  /// Whether the pixel lies on `plane` within the tolerance, and how far.
  bool onPlane(int plane, int u, int v, float z, float& distance) const
  {
    distance = distanceTo(planes_[plane], x_over_z_[u], y_over_z_[v], z);
    return distance <= tolerance(z);
  }

  float tolerance(float z) const { return sigma_factor_ * std::max(sigma_at_1m_ * z * z, sigma_floor_) + floor_; }

  /// Whether the pixels around (u, v) lie closer to plane `a` than to plane
  /// `b`: the sum over a (2 radius + 1)^2 window of |d_a| - |d_b|, over the
  /// pixels on either plane. Near a crease a single pixel's depth noise
  /// decides at random; the window's sum moves the border to where the two
  /// planes meet.
  bool closerAround(int a, int b, int u, int v, int radius) const
  {
    const int u0 = std::max(0, u - radius), u1 = std::min(frame_.depth_m.cols - 1, u + radius);
    const int v0 = std::max(0, v - radius), v1 = std::min(frame_.depth_m.rows - 1, v + radius);
    // Every contested pixel of a border reads a window: its rows are looked
    // up once each.
    const Plane& plane_a = planes_[a];
    const Plane& plane_b = planes_[b];
    float sum = 0.0f;
    for (int y = v0; y <= v1; ++y)
    {
      const DepthRow row = depthRow(y);
      const float y_over_z = y_over_z_[y];
      for (int x = u0; x <= u1; ++x)
      {
        const float z = row.at(x);
        if (z == 0.0f) continue;
        const float x_over_z = x_over_z_[x];
        const float d_a = distanceTo(plane_a, x_over_z, y_over_z, z);
        const float d_b = distanceTo(plane_b, x_over_z, y_over_z, z);
        if (std::min(d_a, d_b) <= tolerance(z)) sum += d_a - d_b;
      }
    }
    return sum < 0.0f;
  }

  /// Labels the pixels of `box` that lie on `plane` (one row at a time, so
  /// the plane's row term is computed once).
  void labelOnPlane(int plane, const cv::Rect& box, cv::Mat& labels) const
  {
    const Plane& p = planes_[plane];
    for (int v = box.y; v < box.br().y; ++v)
    {
      const DepthRow row = depthRow(v);
      int* label_row = labels.ptr<int>(v);
      const float row_term = p.ny * y_over_z_[v] + p.nz;
      for (int u = box.x; u < box.br().x; ++u)
      {
        const float z = row.at(u);
        if (z == 0.0f) continue;
        if (std::abs(z * (p.nx * x_over_z_[u] + row_term) + p.d) <= tolerance(z)) label_row[u] = plane;
      }
    }
  }

private:
  struct Plane
  {
    float nx, ny, nz, d;
  };

  /// Distance of the pixel with ray (x/z, y/z) at depth z from `plane`.
  static float distanceTo(const Plane& plane, float x_over_z, float y_over_z, float z)
  {
    return std::abs(z * (plane.nx * x_over_z + plane.ny * y_over_z + plane.nz) + plane.d);
  }

  const RgbdFrame& frame_;
  const cv::Mat& excluded_;
  /// cv::Mat::empty() is a call into the library: asked once, not per pixel.
  const bool has_excluded_;
  std::vector<Plane> planes_;
  std::vector<float> x_over_z_, y_over_z_;
  float sigma_at_1m_, sigma_floor_, sigma_factor_, floor_;
};

/// Cells inside a plane: labelled, with no plane of another region among
/// their eight neighbours. A neighbour without a plane (a depth edge, a
/// dropout, a crease cell) does not make a cell contested: the cell passed
/// its own planarity tests, and the pixels beyond it are reached by growth
/// anyway. Nor does a plane of the same region (pieces of one bent
/// surface): which of the two takes a pixel there changes no segment.
std::vector<std::uint8_t> innerCells(const CellGrid& grid, const std::vector<int>& cell_labels,
                                     const std::vector<int>& regions)
{
  const int cols = grid.cols(), rows = grid.rows();
  std::vector<std::uint8_t> inner(static_cast<std::size_t>(grid.size()), 0);
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col)
    {
      const int label = cell_labels[row * cols + col];
      if (label < 0) continue;
      bool surrounded = true;
      for (int r = std::max(0, row - 1); r <= std::min(rows - 1, row + 1) && surrounded; ++r)
        for (int c = std::max(0, col - 1); c <= std::min(cols - 1, col + 1) && surrounded; ++c)
        {
          const int other = cell_labels[r * cols + c];
          surrounded = other < 0 || regions[other] == regions[label];
        }
      inner[row * cols + col] = surrounded ? 1 : 0;
    }
  return inner;
}
/// Per cell: the plane a cell without one takes in bulk (its labelled
/// eight neighbours, at least three, are all of that plane), or -1.
std::vector<int> fillPlanes(const CellGrid& grid, const std::vector<int>& cell_labels)
{
  const int cols = grid.cols(), rows = grid.rows();
  std::vector<int> fill(static_cast<std::size_t>(grid.size()), -1);
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col)
    {
      if (cell_labels[row * cols + col] >= 0) continue;
      int plane = -1, labelled = 0;
      bool single = true;
      for (int r = std::max(0, row - 1); r <= std::min(rows - 1, row + 1) && single; ++r)
        for (int c = std::max(0, col - 1); c <= std::min(cols - 1, col + 1) && single; ++c)
        {
          const int label = cell_labels[r * cols + c];
          if (label < 0) continue;
          single = plane < 0 || label == plane;
          plane = label;
          ++labelled;
        }
      if (single && labelled >= 3) fill[row * cols + col] = plane;
    }
  return fill;
}
}  // namespace

void PlaneRefinementParams::validate() const
{
  if (!(pixel_sigma_factor > 0.0)) throw ConfigError("colour-free segmenter: pixel_sigma_factor must be > 0");
  if (contest_radius_px < 0) throw ConfigError("colour-free segmenter: contest_radius_px must be >= 0");
  if (!(pixel_floor_m >= 0.0)) throw ConfigError("colour-free segmenter: pixel_floor_m must be >= 0");
}

void refinePlaneLabels(const RgbdFrame& frame, const PixelRays& rays, const CellGrid& grid,
                       const CellPlanes& cell_planes, const DepthNoise& noise, const cv::Mat& excluded,
                       const PlaneRefinementParams& params, bool parallel, cv::Mat& labels,
                       std::vector<std::uint8_t>* inner_cells)
{
  const int width = frame.width_px(), height = frame.height_px();
  labels.create(height, width, CV_32SC1);
  if (cell_planes.planes.empty())
  {
    labels.setTo(-1);
    if (inner_cells) inner_cells->assign(static_cast<std::size_t>(grid.size()), 0);
    return;
  }
  const int cols = grid.cols(), rows = grid.rows(), cell_px = grid.cellPx();
  const std::vector<int>& cell_labels = cell_planes.cell_labels;

  const std::vector<std::uint8_t> inner = innerCells(grid, cell_labels, cell_planes.regions);
  std::vector<std::uint8_t> plane_has_inner(cell_planes.planes.size(), 0);
  for (int cell = 0; cell < grid.size(); ++cell)
    if (inner[cell]) plane_has_inner[cell_labels[cell]] = 1;
  // Seed cells: the inner ones; a plane too small to have any seeds from
  // all its cells (and those pixels stay open to its neighbours).
  auto isSeedCell = [&](int cell) {
    const int label = cell_labels[cell];
    return label >= 0 && (inner[cell] || !plane_has_inner[label]);
  };
  // Cells without a plane whose planar neighbours are all of one plane (a
  // cell of a face that failed a test by noise, a dropout): their pixels
  // are tested against that plane in bulk rather than grown into one by
  // one. Where far noise leaves many such cells this halves the growth.
  const std::vector<int> fill = fillPlanes(grid, cell_labels);
  auto bulkPlane = [&](int cell) { return isSeedCell(cell) ? cell_labels[cell] : fill[cell]; };

  const PixelTester tester(frame, rays, cell_planes, noise, excluded, params);
  // Every cell is written once: the seeds' pixels on their plane get its
  // label, all others -1 (no separate clearing pass over the image).
  auto labelSeedRows = [&](const cv::Range& cell_rows) {
    for (int row = cell_rows.start; row < cell_rows.end; ++row)
      for (int col = 0; col < cols; ++col)
      {
        const int cell = row * cols + col;
        const cv::Rect box = grid.rect(cell);
        for (int v = box.y; v < box.br().y; ++v) std::fill_n(labels.ptr<int>(v) + box.x, box.width, -1);
        const int plane = bulkPlane(cell);
        if (plane >= 0) tester.labelOnPlane(plane, box, labels);
      }
  };
  if (parallel)
    cv::parallel_for_(cv::Range(0, rows), labelSeedRows);
  else
    labelSeedRows(cv::Range(0, rows));

  // Growth starts from the seed pixels next to an undecided cell: all the
  // labelled pixels of a seed cell that is not inner, the side facing an
  // undecided neighbour of an inner one.
  int* label_data = labels.ptr<int>(0);
  // The queue's storage is kept between frames: a fresh multi-megabyte
  // buffer costs more in page faults than the growth itself.
  thread_local std::vector<int> queue;
  queue.clear();
  auto pushLabelled = [&](const cv::Rect& box) {
    for (int v = box.y; v < box.br().y; ++v)
    {
      const int* label_row = labels.ptr<int>(v);
      for (int u = box.x; u < box.br().x; ++u)
        if (label_row[u] >= 0) queue.push_back(v * width + u);
    }
  };
  // A cell is open when growth still has to decide its pixels.
  auto open = [&](int cell) { return !inner[cell] && fill[cell] < 0; };
  for (int cell = 0; cell < grid.size(); ++cell)
  {
    const cv::Rect box = grid.rect(cell);
    if (fill[cell] >= 0)
    {
      // A filled cell next to an open one passes growth on.
      const int col = cell % cols, row = cell / cols;
      bool next_to_open = false;
      for (int r = std::max(0, row - 1); r <= std::min(rows - 1, row + 1) && !next_to_open; ++r)
        for (int c = std::max(0, col - 1); c <= std::min(cols - 1, col + 1) && !next_to_open; ++c)
          next_to_open = open(r * cols + c);
      if (next_to_open) pushLabelled(box);
      continue;
    }
    if (!isSeedCell(cell)) continue;
    if (!inner[cell])
    {
      pushLabelled(box);
      continue;
    }
    const int col = cell % cols, row = cell / cols;
    if (row > 0 && open(cell - cols)) pushLabelled({box.x, box.y, box.width, 1});
    if (row + 1 < rows && open(cell + cols)) pushLabelled({box.x, box.br().y - 1, box.width, 1});
    if (col > 0 && open(cell - 1)) pushLabelled({box.x, box.y, 1, box.height});
    if (col + 1 < cols && open(cell + 1)) pushLabelled({box.br().x - 1, box.y, 1, box.height});
  }

  // Pixels of inner cells are decided; everything else is open. A pixel
  // goes to the plane it is closest to among those that reach it.
  std::vector<int> cell_of_column(static_cast<std::size_t>(width)), cell_row_of_row(static_cast<std::size_t>(height));
  for (int u = 0; u < width; ++u) cell_of_column[u] = u / cell_px;
  for (int v = 0; v < height; ++v) cell_row_of_row[v] = (v / cell_px) * cols;
  auto locked = [&](int u, int v) { return inner[cell_row_of_row[v] + cell_of_column[u]] != 0; };
  // The plane that last lost a pixel's contest: a plane reaching a pixel
  // from several sides contests it once. Kept between frames; the entries
  // written are reset at the end.
  thread_local std::vector<int> lost;
  thread_local std::vector<int> contested;
  if (lost.size() != static_cast<std::size_t>(width) * height) lost.assign(static_cast<std::size_t>(width) * height, -1);
  contested.clear();
  for (std::size_t head = 0; head < queue.size(); ++head)
  {
    const int pixel = queue[head];
    const int label = label_data[pixel];
    const int v = pixel / width, u = pixel - v * width;
    const int neighbours[4][2] = {{u - 1, v}, {u + 1, v}, {u, v - 1}, {u, v + 1}};
    for (const auto& [nu, nv] : neighbours)
    {
      if (nu < 0 || nv < 0 || nu >= width || nv >= height || locked(nu, nv)) continue;
      const int next = nv * width + nu;
      const int current = label_data[next];
      if (current == label) continue;
      const float z = tester.depth(nu, nv);
      float distance = 0.0f;
      if (z == 0.0f || !tester.onPlane(label, nu, nv, z, distance)) continue;
      if (current >= 0)
      {
        // Within one region either plane will do.
        if (lost[next] == label || cell_planes.regions[current] == cell_planes.regions[label]) continue;
        if (lost[next] < 0) contested.push_back(next);
        const bool wins = tester.closerAround(label, current, nu, nv, params.contest_radius_px);
        lost[next] = wins ? current : label;
        if (!wins) continue;
      }
      label_data[next] = label;
      queue.push_back(next);
    }
  }
  for (const int pixel : contested) lost[pixel] = -1;
  if (inner_cells) *inner_cells = inner;
}

std::vector<PlaneSeam> planeBorders(const RgbdFrame& frame, const PixelRays& rays, const CellGrid& grid,
                                      const cv::Mat& labels, const std::vector<std::uint8_t>& inner_cells)
{
  std::vector<PlaneSeam> borders;
  auto borderOf = [&](int a, int b) -> PlaneSeam& {
    const int first = std::min(a, b), second = std::max(a, b);
    for (PlaneSeam& border : borders)
      if (border.first == first && border.second == second) return border;
    borders.push_back({first, second, 0, {}, {}});
    return borders.back();
  };
  auto addPoint = [&](PlaneSeam& border, int label, int u, int v) {
    const double z = frame.depth_m.ptr<float>(v)[u];
    (label == border.first ? border.first_side : border.second_side).add(rays.x_over_z[u] * z, rays.y_over_z[v] * z, z);
  };
  const int width = labels.cols, height = labels.rows;
  for (int cell = 0; cell < grid.size(); ++cell)
  {
    if (inner_cells[cell]) continue;
    // The cell and one pixel beyond its right and bottom sides.
    const cv::Rect box = grid.rect(cell);
    for (int v = box.y; v < box.br().y; ++v)
    {
      const int* row = labels.ptr<int>(v);
      const int* below = v + 1 < height ? labels.ptr<int>(v + 1) : nullptr;
      for (int u = box.x; u < box.br().x; ++u)
      {
        const int label = row[u];
        if (label < 0) continue;
        if (u + 1 < width && row[u + 1] >= 0 && row[u + 1] != label)
        {
          PlaneSeam& border = borderOf(label, row[u + 1]);
          ++border.length;
          addPoint(border, label, u, v);
          addPoint(border, row[u + 1], u + 1, v);
        }
        if (below && below[u] >= 0 && below[u] != label)
        {
          PlaneSeam& border = borderOf(label, below[u]);
          ++border.length;
          addPoint(border, label, u, v);
          addPoint(border, below[u], u, v + 1);
        }
      }
    }
  }
  return borders;
}
}  // namespace brick_pose
