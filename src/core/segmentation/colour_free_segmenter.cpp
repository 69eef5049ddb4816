#include "brick_pose/segmentation/colour_free_segmenter.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

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

/// A cell of the given support lies within this many depth-noise sigmas of
/// its plane (a cell's mean of correlated noise is hardly better than one
/// pixel's).
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
                                            ColourFreeTimings& t,
                                            const std::optional<Eigen::Vector4d>& given_support) const
{
  if (!excluded.empty() && (excluded.type() != CV_8UC1 || excluded.size() != frame.depth_m.size()))
    throw InputError("colour-free segmenter: the excluded mask must be CV_8UC1 of the frame's size");
  if (frame.depth_m.empty() || frame.depth_m.type() != CV_32FC1)
    throw InputError("colour-free segmenter: the frame has no CV_32FC1 depth");

  StageClock clock;
  const PixelRays rays(frame.camera);
  const CellGrid grid(frame, rays, cellPx(frame.width_px()), excluded, params_.parallel);
  // The cells of a given support are not clustered (on a pile seen from
  // above they are most of the image): they join one plane fitted to them
  // afterwards, which takes its pixels in the refinement as the clustered
  // ground did. The noise is still measured on every cell.
  DepthNoise noise;
  noise.floor_m = params_.noise_floor_m;
  noise.sigma_at_1m_m = params_.estimate_noise ? measuredNoiseAt1m(grid) : params_.noise_at_1m_m;
  noise.correlated_points = static_cast<double>(params_.noise_correlation_px) * params_.noise_correlation_px;
  const std::vector<std::uint8_t> on_support =
      given_support ? cellsOnSupport(grid, *given_support, noise) : std::vector<std::uint8_t>();
  const std::vector<MomentPlane> cell_planes =
      fitCellPlanes(grid, params_.clustering.min_cell_fill, params_.parallel, on_support);
  t.noise_at_1m_m = noise.sigma_at_1m_m;
  clock.stop(t.cells_ms, t.cells_cpu_ms);

  clock = StageClock();
  CellPlanes planes = clustering_.cluster(grid, cell_planes, noise);
  if (given_support) addSupportPlane(grid, *given_support, on_support, noise, planes);
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
                                                  const std::optional<Eigen::Vector4d>& given_support) const
{
  PlanarSegments result;
  // No face fits an image smaller than the smallest segment.
  if (frame.depth_m.rows * frame.depth_m.cols < params_.min_area_px) return result;
  ColourFreeTimings local;
  ColourFreeTimings& t = timings ? *timings : local;
  // The label image is working memory kept between frames (a fresh one
  // costs more in page faults than filling it).
  thread_local cv::Mat labels;
  const CellPlanes planes = labelPlanes(frame, excluded, labels, t, given_support);
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
    if (given_support)
      for (std::size_t r = 0; r < region_planes.size(); ++r)
        supporting[r] = region_planes[r].valid && area_px[r] > 0 &&
                        onGivenSupport(region_planes[r], *given_support, params_.clustering.min_angle_deg);
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

std::vector<std::uint8_t> ColourFreeSegmenter::cellsOnSupport(const CellGrid& grid, const Eigen::Vector4d& support,
                                                               const DepthNoise& noise) const
{
  // Without a plane of their own (none is fitted for them): their mean
  // within support_margin_m of the support, and flat about its normal as
  // the clustering wants a node flat about its own. The foot of a side, the
  // ground mixed with something on it, keep their planes and clusters.
  const double min_points = std::max(3.0, params_.clustering.min_cell_fill * grid.cellPx() * grid.cellPx());
  std::vector<std::uint8_t> on(static_cast<std::size_t>(grid.size()), 0);
  MomentPlane level;
  level.normal = support.head<3>();
  level.valid = true;
  for (int cell = 0; cell < grid.size(); ++cell)
  {
    const PlaneMoments& moments = grid.moments(cell);
    if (moments.count < min_points) continue;
    level.centroid_m = moments.mean();
    if (std::abs(level.normal.dot(level.centroid_m) + support[3]) > params_.support_margin_m) continue;
    level.count = moments.count;
    level.mse_m2 = level.normal.dot(moments.covariance() * level.normal);
    on[cell] = clustering_.planarCell(grid, cell, level, noise);
  }
  return on;
}

void ColourFreeSegmenter::addSupportPlane(const CellGrid& grid, const Eigen::Vector4d& support,
                                          std::vector<std::uint8_t> on_support, const DepthNoise& noise,
                                          CellPlanes& planes) const
{
  // The candidates may hold something low lying on the support, or the foot
  // of a side: the clustering kept those out of the ground's node. Here the
  // cells at the candidates' median height are the support's, within the
  // noise, and once more those within the noise of the plane fitted to them.
  std::vector<double> heights_m;
  for (int cell = 0; cell < grid.size(); ++cell)
    if (on_support[cell]) heights_m.push_back(support.head<3>().dot(grid.moments(cell).mean()) + support[3]);
  if (heights_m.empty()) return;
  const double median_m = upperMedianInPlace(heights_m);
  auto keepNear = [&](const std::function<double(const Eigen::Vector3d&)>& offset_m) {
    PlaneMoments moments;
    for (int cell = 0; cell < grid.size(); ++cell)
    {
      if (!on_support[cell]) continue;
      const Eigen::Vector3d mean = grid.moments(cell).mean();
      on_support[cell] = std::abs(offset_m(mean)) <= kSupportCellSigmas * noise.sigma(mean.z());
      if (on_support[cell]) moments += grid.moments(cell);
    }
    return moments;
  };
  PlaneMoments moments =
      keepNear([&](const Eigen::Vector3d& mean) { return support.head<3>().dot(mean) + support[3] - median_m; });
  MomentPlane plane = fitMomentPlane(moments);
  if (!plane.valid) return;
  moments = keepNear([&](const Eigen::Vector3d& mean) { return plane.signedDistance(mean); });
  plane = fitMomentPlane(moments);
  if (!plane.valid) return;
  // Only the cells the clustering would have taken for nodes join it (a
  // cell of the ground mixed with the foot of a box stays open to both in
  // the refinement, as before): flat about the plane's normal, within the
  // noise, with no depth step.
  const int index = static_cast<int>(planes.planes.size());
  int cells = 0;
  for (int cell = 0; cell < grid.size(); ++cell)
  {
    if (!on_support[cell]) continue;
    MomentPlane about = plane;
    about.centroid_m = grid.moments(cell).mean();
    about.count = grid.moments(cell).count;
    about.mse_m2 = plane.normal.dot(grid.moments(cell).covariance() * plane.normal);
    if (!clustering_.planarCell(grid, cell, about, noise)) continue;
    planes.cell_labels[cell] = index;
    ++cells;
  }
  planes.planes.push_back(plane);
  planes.moments.push_back(moments);
  planes.cell_counts.push_back(cells);
  planes.regions.push_back(planes.region_count++);
}

bool ColourFreeSegmenter::onGivenSupport(const MomentPlane& plane, const Eigen::Vector4d& support,
                                         double max_tilt_deg) const
{
  const Eigen::Vector3d up = support.head<3>();
  return std::abs(up.dot(plane.centroid_m) + support[3]) <= params_.support_margin_m &&
         std::abs(up.dot(plane.normal)) >= std::cos(max_tilt_deg * kDegToRad);
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
  // Pieces of the same support the clustering left apart.
  const double min_cos = std::cos(params_.clustering.min_angle_deg * 3.14159265358979323846 / 180.0);
  for (std::size_t r = 0; r < planes.size(); ++r)
    supporting[r] = static_cast<int>(r) == best ||
                    (planes[r].valid && area_px[r] > 0 && std::abs(above(planes[best], planes[r])) <= margin_m &&
                     planes[r].normal.dot(planes[best].normal) >= min_cos);
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
