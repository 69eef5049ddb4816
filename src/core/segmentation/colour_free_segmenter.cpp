#include "brick_pose/segmentation/colour_free_segmenter.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/segmentation/cell_grid.h"
#include "brick_pose/segmentation/depth_noise.h"

namespace brick_pose
{
namespace
{
using Clock = std::chrono::steady_clock;

/// The noise is measured on blocks of this many cells square: several
/// times the noise's correlation length, so that a block's plane cannot
/// absorb the correlated part (on the rig's correlated D415 noise, blocks of
/// 2, 3 and 4 cells of 8 px read 0.74, 0.85 and 0.93 of the true sigma), yet
/// small enough that most blocks lie on one face.
constexpr int kNoiseBlockCells = 4;

double millisecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

void require(bool condition, const char* field, const char* rule)
{
  if (!condition) throw ConfigError(std::string("colour-free segmenter: ") + field + " " + rule);
}

/// Pixel count and bounding box of one plane's pixels.
struct Extent
{
  int count = 0;
  int u_min = 0, v_min = 0, u_max = -1, v_max = -1;

  cv::Rect box() const { return {u_min, v_min, u_max - u_min + 1, v_max - v_min + 1}; }
};

std::vector<Extent> planeExtents(const cv::Mat& labels, int plane_count)
{
  std::vector<Extent> extents(static_cast<std::size_t>(plane_count));
  for (int v = 0; v < labels.rows; ++v)
  {
    const int* row = labels.ptr<int>(v);
    for (int u = 0; u < labels.cols; ++u)
    {
      const int label = row[u];
      if (label < 0) continue;
      Extent& e = extents[label];
      if (e.count++ == 0)
      {
        e.u_min = e.u_max = u;
        e.v_min = e.v_max = v;
        continue;
      }
      e.u_min = std::min(e.u_min, u);
      e.u_max = std::max(e.u_max, u);
      e.v_max = v;  // rows are visited in order
    }
  }
  return extents;
}

/// The connected parts (8-connected) of one plane's pixels inside `box`, as
/// segments of at least `min_area_px`. Holes without depth inside a part
/// (dropouts) are closed into its mask: the outline comes from the image.
void appendPlaneSegments(const cv::Mat& labels, int label, const cv::Rect& box, int min_area_px,
                         std::vector<Segment>& segments)
{
  const cv::Mat region = labels(box);
  cv::Mat mine, open;
  cv::compare(region, label, mine, cv::CMP_EQ);
  cv::compare(region, 0, open, cv::CMP_LT);
  cv::Mat closed;
  cv::morphologyEx(mine, closed, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  // Closing may only add pixels no plane has.
  cv::bitwise_and(closed, mine | open, closed);

  cv::Mat components, stats, centroids;
  const int count = cv::connectedComponentsWithStats(closed, components, stats, centroids, 8, CV_32S);
  for (int k = 1; k < count; ++k)
  {
    const int area = stats.at<int>(k, cv::CC_STAT_AREA);
    if (area < min_area_px) continue;
    const cv::Rect local(stats.at<int>(k, cv::CC_STAT_LEFT), stats.at<int>(k, cv::CC_STAT_TOP),
                         stats.at<int>(k, cv::CC_STAT_WIDTH), stats.at<int>(k, cv::CC_STAT_HEIGHT));
    Segment segment;
    segment.bounding_box_px = local + box.tl();
    segment.area_px = area;
    segment.mask = cv::Mat::zeros(local.size(), CV_8UC1);
    segment.pixel_indices.reserve(static_cast<std::size_t>(area));
    for (int y = local.y; y < local.br().y; ++y)
    {
      const int* component_row = components.ptr<int>(y);
      const int* label_row = region.ptr<int>(y);
      std::uint8_t* mask_row = segment.mask.ptr<std::uint8_t>(y - local.y);
      const int v = y + box.y;
      for (int x = local.x; x < local.br().x; ++x)
      {
        if (component_row[x] != k) continue;
        mask_row[x - local.x] = 255;
        if (label_row[x] == label) segment.pixel_indices.push_back(v * labels.cols + x + box.x);
      }
    }
    segments.push_back(std::move(segment));
  }
}
}  // namespace

void ColourFreeParams::validate() const
{
  require(cell_px >= 2, "cell_px", "must be >= 2");
  require(noise_at_1m_m > 0.0, "noise_at_1m_m", "must be > 0");
  require(min_noise_at_1m_m > 0.0, "min_noise_at_1m_m", "must be > 0");
  require(max_noise_at_1m_m >= min_noise_at_1m_m, "max_noise_at_1m_m", "must be >= min_noise_at_1m_m");
  require(noise_quantile > 0.0 && noise_quantile < 1.0, "noise_quantile", "must be in (0, 1)");
  require(noise_floor_m >= 0.0, "noise_floor_m", "must be >= 0");
  require(noise_correlation_px >= 1, "noise_correlation_px", "must be >= 1");
  require(min_area_px >= 1, "min_area_px", "must be >= 1");
  clustering.validate();
  refinement.validate();
}

ColourFreeSegmenter::ColourFreeSegmenter(const ColourFreeParams& params)
  : params_(params), clustering_(params.clustering)
{
  params_.validate();
}

cv::Mat ColourFreeSegmenter::labelRegions(const RgbdFrame& frame, const cv::Mat& excluded,
                                         ColourFreeTimings* timings) const
{
  if (!excluded.empty() && (excluded.type() != CV_8UC1 || excluded.size() != frame.depth_m.size()))
    throw InputError("colour-free segmenter: the excluded mask must be CV_8UC1 of the frame's size");
  if (frame.depth_m.empty() || frame.depth_m.type() != CV_32FC1)
    throw InputError("colour-free segmenter: the frame has no CV_32FC1 depth");
  ColourFreeTimings local;
  ColourFreeTimings& t = timings ? *timings : local;

  auto start = Clock::now();
  const PixelRays rays(frame.camera);
  const CellGrid grid(frame, rays, params_.cell_px, excluded, params_.parallel);
  const std::vector<MomentPlane> cell_planes = fitCellPlanes(grid, params_.clustering.min_cell_fill);
  DepthNoise noise;
  noise.floor_m = params_.noise_floor_m;
  noise.sigma_at_1m_m = params_.estimate_noise ? measuredNoiseAt1m(grid) : params_.noise_at_1m_m;
  noise.correlated_points = static_cast<double>(params_.noise_correlation_px) * params_.noise_correlation_px;
  t.noise_at_1m_m = noise.sigma_at_1m_m;
  t.cells_ms = millisecondsSince(start);

  start = Clock::now();
  const CellPlanes planes = clustering_.cluster(grid, cell_planes, noise);
  t.planes = static_cast<int>(planes.planes.size());
  t.clustering_ms = millisecondsSince(start);

  start = Clock::now();
  cv::Mat labels = refinePlaneLabels(frame, rays, grid, planes, noise, excluded, params_.refinement, params_.parallel);
  t.regions = planes.region_count;
  if (planes.region_count < static_cast<int>(planes.planes.size()))
  {
    auto toRegions = [&](const cv::Range& rows) {
      for (int v = rows.start; v < rows.end; ++v)
      {
        int* row = labels.ptr<int>(v);
        for (int u = 0; u < labels.cols; ++u)
          if (row[u] >= 0) row[u] = planes.regions[row[u]];
      }
    };
    if (params_.parallel)
      cv::parallel_for_(cv::Range(0, labels.rows), toRegions);
    else
      toRegions(cv::Range(0, labels.rows));
  }
  t.refinement_ms = millisecondsSince(start);
  return labels;
}

std::vector<Segment> ColourFreeSegmenter::segment(const RgbdFrame& frame, const cv::Mat& excluded,
                                                  ColourFreeTimings* timings) const
{
  // No face fits an image smaller than the smallest segment.
  if (frame.depth_m.rows * frame.depth_m.cols < params_.min_area_px) return {};
  ColourFreeTimings local;
  ColourFreeTimings& t = timings ? *timings : local;
  const cv::Mat labels = labelRegions(frame, excluded, &t);
  const auto start = Clock::now();
  std::vector<Segment> segments = segmentsFromLabels(frame, labels);
  t.segments_ms = millisecondsSince(start);
  return segments;
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

std::vector<Segment> ColourFreeSegmenter::segmentsFromLabels(const RgbdFrame& frame, const cv::Mat& labels) const
{
  double max_label = -1.0;
  cv::minMaxLoc(labels, nullptr, &max_label);
  const int plane_count = static_cast<int>(max_label) + 1;
  if (plane_count <= 0) return {};
  const std::vector<Extent> extents = planeExtents(labels, plane_count);
  std::vector<Segment> segments;
  for (int label = 0; label < plane_count; ++label)
  {
    // Closing fills dropouts, so a plane with half the area in depth
    // pixels may still reach it.
    if (2 * extents[label].count < params_.min_area_px) continue;
    appendPlaneSegments(labels, label, extents[label].box(), params_.min_area_px, segments);
  }
  std::sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) { return a.area_px > b.area_px; });
  return segments;
}
}  // namespace brick_pose
