#pragma once
// The organised frame cut into square pixel blocks ("cells"), each with the
// plane moments of its 3D points: the nodes the colour-free segmenter
// clusters. Cells on the right and bottom border may be smaller than the
// others; a cell needs most of a full cell's pixels with depth to count.

#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/segmentation/plane_moments.h"

namespace brick_pose
{
/// x / z and y / z of the ray through each column and row: back-projection
/// of pixel (u, v) at depth z is (x_over_z[u] z, y_over_z[v] z, z).
struct PixelRays
{
  std::vector<double> x_over_z;
  std::vector<double> y_over_z;

  explicit PixelRays(const PinholeCamera& camera);
};

class CellGrid
{
public:
  /// Accumulates the cells of `frame`. Pixels without depth, and pixels that
  /// are non-zero in `excluded` (CV_8UC1 of the frame's size, or empty), are
  /// left out. With `parallel`, rows of cells are split over OpenCV's threads.
  CellGrid(const RgbdFrame& frame, const PixelRays& rays, int cell_px, const cv::Mat& excluded, bool parallel);

  int cellPx() const { return cell_px_; }
  int cols() const { return cols_; }
  int rows() const { return rows_; }
  int size() const { return cols_ * rows_; }
  /// The pixels of cell `index` (row-major over the grid).
  cv::Rect rect(int index) const;
  int indexOfPixel(int u_px, int v_px) const { return (v_px / cell_px_) * cols_ + u_px / cell_px_; }
  const PlaneMoments& moments(int index) const { return moments_[index]; }
  /// Largest depth difference between horizontally / vertically adjacent
  /// pixels of the cell (metres): a plane through the two sides of a depth
  /// step can fit a cell's points well, its pixel-to-pixel steps cannot.
  float maxStepU(int index) const { return max_step_u_m_[index]; }
  float maxStepV(int index) const { return max_step_v_m_[index]; }
  /// Focal lengths of the frame's camera (pixels).
  double fx() const { return fx_px_; }
  double fy() const { return fy_px_; }

private:
  int cell_px_;
  int cols_;
  int rows_;
  int width_px_;
  int height_px_;
  double fx_px_;
  double fy_px_;
  std::vector<PlaneMoments> moments_;
  std::vector<float> max_step_u_m_;
  std::vector<float> max_step_v_m_;
};
}  // namespace brick_pose
