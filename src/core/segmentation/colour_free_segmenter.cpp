#include "brick_pose/segmentation/colour_free_segmenter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <string>

#include <opencv2/core/utility.hpp>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/elapsed.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/segmentation/cell_grid.h"
#include "brick_pose/segmentation/depth_noise.h"
#include "brick_pose/segmentation/label_segments.h"

namespace brick_pose
{
namespace
{
/// The noise is measured on blocks of this many cells square: several
/// times the noise's correlation length, so that a block's plane cannot
/// absorb the correlated part (on the rig's correlated D415 noise, blocks of
/// 2, 3 and 4 cells of 8 px read 0.74, 0.85 and 0.93 of the true sigma), yet
/// small enough that most blocks lie on one face.
constexpr int kNoiseBlockCells = 4;
/// A cell of a given support lies within this many noise sigmas (of one
/// pixel's depth at its mean's distance) of the support's plane.
constexpr double kSupportCellSigmas = 3.0;

/// Wall and calling-thread CPU time of a stage (the CPU time stays
/// meaningful on a machine shared with other processes).
class StageClock
{
public:
  StageClock() : wall_(SteadyClock::now()), cpu_s_(threadCpuSeconds()) {}
  void stop(double& wall_ms, double& cpu_ms) const
  {
    wall_ms = millisecondsSince(wall_);
    cpu_ms = 1e3 * (threadCpuSeconds() - cpu_s_);
  }

private:
  SteadyClock::time_point wall_;
  double cpu_s_;
};

}  // namespace

void ColourFreeParams::validate() const
{
  const ParamCheck check("colour-free segmenter");
  check.require(cell_px == 0 || cell_px >= 2, "cell_px", "must be 0 (automatic) or >= 2");
  check.require(cells_across > 0, "cells_across", "must be > 0");
  check.require(max_gap_px >= 0, "max_gap_px", "must be >= 0");
  check.require(support_min_image_fraction > 0.0 && support_min_image_fraction <= 1.0, "support_min_image_fraction",
          "must be in (0, 1]");
  check.require(support_margin_m >= 0.0, "support_margin_m", "must be >= 0");
  check.require(noise_at_1m_m > 0.0, "noise_at_1m_m", "must be > 0");
  check.require(min_noise_at_1m_m > 0.0, "min_noise_at_1m_m", "must be > 0");
  check.require(max_noise_at_1m_m >= min_noise_at_1m_m, "max_noise_at_1m_m", "must be >= min_noise_at_1m_m");
  check.require(noise_quantile > 0.0 && noise_quantile < 1.0, "noise_quantile", "must be in (0, 1)");
  check.require(noise_floor_m >= 0.0, "noise_floor_m", "must be >= 0");
  check.require(noise_correlation_px >= 1, "noise_correlation_px", "must be >= 1");
  check.require(min_area_px >= 1, "min_area_px", "must be >= 1");
  clustering.validate();
  refinement.validate();
}

ColourFreeSegmenter::ColourFreeSegmenter(const ColourFreeParams& params)
  : params_(params), clustering_(params.clustering)
{
  params_.validate();
}

int ColourFreeSegmenter::cellPx(int width_px) const
{
  if (params_.cell_px > 0) return params_.cell_px;
  return std::max(4, static_cast<int>(std::lround(width_px / params_.cells_across)));
}

CellPlanes ColourFreeSegmenter::labelPlanes(const RgbdFrame& frame, const cv::Mat& excluded, cv::Mat& labels,
                                            ColourFreeTimings& t, const std::optional<Eigen::Vector4d>& seeded) const
{
  if (!excluded.empty() && (excluded.type() != CV_8UC1 || excluded.size() != frame.depth_m.size()))
    throw InputError("colour-free segmenter: the excluded mask must be CV_8UC1 of the frame's size");
  if (frame.depth_m.empty() || frame.depth_m.type() != CV_32FC1)
    throw InputError("colour-free segmenter: the frame has no CV_32FC1 depth");

  StageClock clock;
  const PixelRays rays(frame.camera);
  const CellGrid grid(frame, rays, cellPx(frame.width_px()), excluded, params_.parallel);
  const std::vector<MomentPlane> cell_planes = fitCellPlanes(grid, params_.clustering.min_cell_fill, params_.parallel);
  DepthNoise noise;
  noise.floor_m = params_.noise_floor_m;
  noise.sigma_at_1m_m = params_.estimate_noise ? measuredNoiseAt1m(grid) : params_.noise_at_1m_m;
  noise.correlated_points = static_cast<double>(params_.noise_correlation_px) * params_.noise_correlation_px;
  t.noise_at_1m_m = noise.sigma_at_1m_m;
  clock.stop(t.cells_ms, t.cells_cpu_ms);

  clock = StageClock();
  // The support's inside (or the likely plane's) starts the clustering as
  // one node: on a pile seen from above it is most of the cells, and
  // merging them one by one was most of the clustering's time.
  const std::vector<std::uint8_t> seeds =
      seeded ? innerSupportCells(grid, cell_planes, noise, *seeded) : std::vector<std::uint8_t>();
  CellPlanes planes = clustering_.cluster(grid, cell_planes, noise, seeds, &t.seeded_cells);
  t.planes = static_cast<int>(planes.planes.size());
  clock.stop(t.clustering_ms, t.clustering_cpu_ms);

  clock = StageClock();
  std::vector<std::uint8_t> inner_cells;
  refinePlaneLabels(frame, rays, grid, planes, noise, excluded, params_.refinement, params_.parallel, labels,
                    &inner_cells);
  // A border of a cell's side at least: a few flying pixels between two
  // faces with a gap do not join them.
  if (planes.region_count > 1)
    clustering_.joinTouchingRegions(planeBorders(frame, rays, grid, labels, inner_cells), grid.cellPx(), noise, planes);
  t.regions = planes.region_count;
  clock.stop(t.refinement_ms, t.refinement_cpu_ms);
  return planes;
}

cv::Mat ColourFreeSegmenter::labelRegions(const RgbdFrame& frame, const cv::Mat& excluded,
                                          ColourFreeTimings* timings) const
{
  ColourFreeTimings local;
  cv::Mat labels;
  const CellPlanes planes = labelPlanes(frame, excluded, labels, timings ? *timings : local);
  for (int v = 0; v < labels.rows; ++v)
  {
    int* row = labels.ptr<int>(v);
    for (int u = 0; u < labels.cols; ++u)
      if (row[u] >= 0) row[u] = planes.regions[row[u]];
  }
  return labels;
}

std::vector<Segment> ColourFreeSegmenter::segment(const RgbdFrame& frame, const cv::Mat& excluded,
                                                  ColourFreeTimings* timings) const
{
  return segmentPlanes(frame, excluded, timings).segments;
}

PlanarSegments ColourFreeSegmenter::segmentPlanes(const RgbdFrame& frame, const cv::Mat& excluded,
                                                  ColourFreeTimings* timings, bool with_supporting,
                                                  const std::optional<Eigen::Vector4d>& given_support,
                                                  const std::optional<Eigen::Vector4d>& likely_plane) const
{
  PlanarSegments result;
  auto unit = [](const std::optional<Eigen::Vector4d>& plane, const char* what) -> std::optional<Eigen::Vector4d> {
    if (!plane) return std::nullopt;
    if (!(plane->allFinite() && plane->head<3>().norm() > 1e-9))
      throw InputError(std::string("colour-free segmenter: the ") + what + " must be finite, with a non-zero normal");
    return *plane / plane->head<3>().norm();
  };
  const std::optional<Eigen::Vector4d> support = unit(given_support, "given support plane");
  const std::optional<Eigen::Vector4d> seeded = support ? support : unit(likely_plane, "likely plane");
  // No face fits an image smaller than the smallest segment.
  if (frame.depth_m.rows * frame.depth_m.cols < params_.min_area_px) return result;
  ColourFreeTimings local;
  ColourFreeTimings& t = timings ? *timings : local;
  // The label image is working memory kept between frames (a fresh one
  // costs more in page faults than filling it).
  thread_local cv::Mat labels;
  const CellPlanes planes = labelPlanes(frame, excluded, labels, t, seeded);
  const StageClock clock;
  // Plane of each region; its size (the area of its segments) comes from
  // the segment extraction, which then leaves out the supporting plane's
  // segments when they are not wanted.
  std::vector<PlaneMoments> region_moments(static_cast<std::size_t>(planes.region_count));
  for (std::size_t i = 0; i < planes.planes.size(); ++i) region_moments[planes.regions[i]] += planes.moments[i];
  std::vector<MomentPlane> region_planes(region_moments.size());
  for (std::size_t r = 0; r < region_moments.size(); ++r) region_planes[r] = fitMomentPlane(region_moments[r]);
  std::vector<bool> supporting(region_moments.size(), false);
  const RegionDropper findSupporting = [&](const std::vector<int>& region_area_px) {
    std::vector<int> area_px(region_moments.size(), 0);
    std::copy_n(region_area_px.begin(), std::min(region_area_px.size(), area_px.size()), area_px.begin());
    if (support)
      for (std::size_t r = 0; r < region_planes.size(); ++r)
        supporting[r] = onSupport(region_planes[r], area_px[r], *support);
    else
      supporting = supportingRegions(region_planes, area_px, frame.width_px() * frame.height_px());
    return with_supporting ? std::vector<bool>() : supporting;
  };
  std::vector<int> segment_regions;
  result.segments = segmentsFromLabels(labels, planes.regions, params_.min_area_px, params_.max_gap_px,
                                       &segment_regions, findSupporting);

  for (std::size_t k = 0; k < result.segments.size(); ++k)
  {
    result.planes.push_back(region_planes[segment_regions[k]]);
    result.supporting.push_back(supporting[segment_regions[k]]);
  }
  clock.stop(t.segments_ms, t.segments_cpu_ms);
  return result;
}

std::vector<std::uint8_t> ColourFreeSegmenter::innerSupportCells(const CellGrid& grid,
                                                                  const std::vector<MomentPlane>& cell_planes,
                                                                  const DepthNoise& noise,
                                                                  const Eigen::Vector4d& support) const
{
  // On the support: a node of its own (planarCell), its mean within
  // support_margin_m, and flat about the support's normal as planarCell
  // wants a node flat about its own. (A single cell's own normal far away
  // is mostly noise: at 2 m most ground cells would fail the clustering's
  // merge angle.)
  MomentPlane level;
  level.normal = support.head<3>();
  level.valid = true;
  std::vector<std::uint8_t> near(static_cast<std::size_t>(grid.size()), 0);
  for (int cell = 0; cell < grid.size(); ++cell)
  {
    const MomentPlane& plane = cell_planes[static_cast<std::size_t>(cell)];
    if (!plane.valid || std::abs(level.normal.dot(plane.centroid_m) + support[3]) > params_.support_margin_m) continue;
    if (!clustering_.planarCell(grid, cell, plane, noise)) continue;
    const PlaneMoments& moments = grid.moments(cell);
    level.centroid_m = plane.centroid_m;
    level.count = moments.count;
    level.mse_m2 = level.normal.dot(moments.covariance() * level.normal);
    near[cell] = clustering_.planarCell(grid, cell, level, noise);
  }
  return insideOf(onOnePlane(grid, near, support, noise), grid.cols(), grid.rows());
}

std::vector<std::uint8_t> ColourFreeSegmenter::onOnePlane(const CellGrid& grid, const std::vector<std::uint8_t>& near,
                                                          const Eigen::Vector4d& support, const DepthNoise& noise)
{
  // Something low on the support (a sheet, a flat box) lies within
  // support_margin_m of it too, and the given plane may be a little off
  // the ground seen: the cells at the candidates' median height make a
  // first plane, and the candidates within the noise of it the support.
  std::vector<double> heights_m;
  for (int cell = 0; cell < grid.size(); ++cell)
    if (near[cell]) heights_m.push_back(support.head<3>().dot(grid.moments(cell).mean()) + support[3]);
  std::vector<std::uint8_t> on(near.size(), 0);
  if (heights_m.empty()) return on;
  const double median_m = upperMedianInPlace(heights_m);
  auto within = [&](const std::function<double(const Eigen::Vector3d&)>& offset_m) {
    PlaneMoments moments;
    for (int cell = 0; cell < grid.size(); ++cell)
    {
      if (!near[cell]) continue;
      const Eigen::Vector3d mean = grid.moments(cell).mean();
      on[cell] = std::abs(offset_m(mean)) <= kSupportCellSigmas * noise.sigma(mean.z()) ? 1 : 0;
      if (on[cell]) moments += grid.moments(cell);
    }
    return moments;
  };
  const MomentPlane first =
      fitMomentPlane(within([&](const Eigen::Vector3d& mean) { return support.head<3>().dot(mean) + support[3] - median_m; }));
  if (!first.valid) return std::vector<std::uint8_t>(near.size(), 0);
  within([&](const Eigen::Vector3d& mean) { return first.signedDistance(mean); });
  return on;
}

std::vector<std::uint8_t> ColourFreeSegmenter::insideOf(const std::vector<std::uint8_t>& cells, int cols, int rows)
{
  // Inside: its eight neighbours in the set too. The cells at the support's
  // border (the foot of a side, the ground beside a box: at 2 m a cell of a
  // box side 7 cm tall spans less height than the noise) are clustered as
  // any other, against the support's node as it grows.
  std::vector<std::uint8_t> inner(cells.size(), 0);
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col)
    {
      bool all_in = cells[static_cast<std::size_t>(row) * cols + col] != 0;
      for (int r = std::max(0, row - 1); r <= std::min(rows - 1, row + 1) && all_in; ++r)
        for (int c = std::max(0, col - 1); c <= std::min(cols - 1, col + 1) && all_in; ++c)
          all_in = cells[static_cast<std::size_t>(r) * cols + c] != 0;
      inner[static_cast<std::size_t>(row) * cols + col] = all_in ? 1 : 0;
    }
  return inner;
}

bool ColourFreeSegmenter::onSupport(const MomentPlane& plane, int area_px, const Eigen::Vector4d& support) const
{
  const Eigen::Vector3d up = support.head<3>();
  return plane.valid && area_px > 0 && std::abs(up.dot(plane.centroid_m) + support[3]) <= params_.support_margin_m &&
         std::abs(up.dot(plane.normal)) >= std::cos(params_.clustering.min_angle_deg * kDegToRad);
}

std::vector<bool> ColourFreeSegmenter::supportingRegions(const std::vector<MomentPlane>& planes,
                                                         const std::vector<int>& area_px, int image_area_px) const
{
  std::vector<bool> supporting(planes.size(), false);
  const double margin_m = params_.support_margin_m;
  auto above = [&](const MomentPlane& base, const MomentPlane& other) { return base.signedDistance(other.centroid_m); };
  int best = -1;
  for (std::size_t r = 0; r < planes.size(); ++r)
  {
    if (!planes[r].valid || area_px[r] < params_.support_min_image_fraction * image_area_px) continue;
    if (best >= 0 && area_px[r] <= area_px[best]) continue;
    bool nothing_below = true, something_on = false;
    for (std::size_t q = 0; q < planes.size() && nothing_below; ++q)
    {
      if (q == r || !planes[q].valid || area_px[q] == 0) continue;
      const double height_m = above(planes[r], planes[q]);
      nothing_below = height_m >= -margin_m;
      something_on = something_on || height_m > margin_m;
    }
    if (nothing_below && something_on) best = static_cast<int>(r);
  }
  if (best < 0) return supporting;
  // Pieces of the same support the clustering left apart. (Both normals
  // face the camera: parallel planes' normals agree in sign.)
  const MomentPlane& base = planes[best];
  Eigen::Vector4d support;
  support << base.normal, -base.normal.dot(base.centroid_m);
  for (std::size_t r = 0; r < planes.size(); ++r)
    supporting[r] = static_cast<int>(r) == best || onSupport(planes[r], area_px[r], support);
  return supporting;
}

double ColourFreeSegmenter::measuredNoiseAt1m(const CellGrid& grid) const
{
  // Residuals of blocks of cells rather than of single cells: a cell's plane
  // absorbs the part of the noise correlated over the stereo matching
  // window, which the merges of larger nodes do see.
  const double min_points = std::max(3.0, params_.clustering.min_cell_fill * grid.cellPx() * grid.cellPx());
  std::vector<double> normalised_mse;
  normalised_mse.reserve(static_cast<std::size_t>(grid.size() / 4 + 1));
  const int side = kNoiseBlockCells;
  for (int row = 0; row + side <= grid.rows(); row += side)
    for (int col = 0; col + side <= grid.cols(); col += side)
    {
      PlaneMoments block;
      bool full = true;
      for (int r = row; r < row + side && full; ++r)
        for (int c = col; c < col + side && full; ++c)
        {
          full = grid.moments(r * grid.cols() + c).count >= min_points;
          block += grid.moments(r * grid.cols() + c);
        }
      if (!full) continue;
      const MomentPlane plane = fitMomentPlane(block);
      if (!plane.valid) continue;
      const double z2 = plane.centroid_m.z() * plane.centroid_m.z();
      normalised_mse.push_back(plane.mse_m2 / (z2 * z2));
    }
  return estimateNoiseAt1m(std::move(normalised_mse), params_.noise_quantile, params_.min_noise_at_1m_m,
                           params_.max_noise_at_1m_m, params_.noise_at_1m_m);
}

}  // namespace brick_pose
