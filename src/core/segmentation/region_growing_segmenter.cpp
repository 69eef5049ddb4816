// PCL normal estimation and region growing are instantiated here only, on
// PointXYZ/Normal, which PCL precompiles.
#include "brick_pose/segmentation/region_growing_segmenter.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>
#include <pcl/features/integral_image_normal.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/organized_cloud.h"
#include "brick_pose/roi/plane_fit.h"

namespace brick_pose
{
namespace
{
constexpr double kPi = 3.14159265358979323846;

void require(bool condition, const char* field, const char* rule)
{
  if (!condition) throw ConfigError(std::string("region growing: ") + field + " " + rule);
}

/// Footprint of one region at full resolution: the pixels inside the
/// region's (dilated) strided cells, or, when regrowing, the connected set of
/// pixels on the region's plane that touches the region.
Segment footprint(const RgbdFrame& frame, const pcl::PointCloud<pcl::PointXYZ>& strided,
                  const std::vector<int>& source_pixels, const pcl::PointIndices& region,
                  const RegionGrowingParams& params)
{
  const int width = frame.width_px();
  const int height = frame.height_px();
  const int stride = params.stride_px;

  // Seed mask: the block of full-resolution pixels around every region point.
  int u_min = width, v_min = height, u_max = -1, v_max = -1;
  for (const int index : region.indices)
  {
    const int pixel = source_pixels[index];
    u_min = std::min(u_min, pixel % width);
    u_max = std::max(u_max, pixel % width);
    v_min = std::min(v_min, pixel / width);
    v_max = std::max(v_max, pixel / width);
  }
  // Region growing leaves out a band of a few strided cells at the border.
  const int margin = params.regrow_footprint ? 8 * stride : stride;
  const cv::Rect box = cv::Rect(cv::Point(u_min - margin, v_min - margin), cv::Point(u_max + margin + 1, v_max + margin + 1)) &
                       cv::Rect(0, 0, width, height);
  cv::Mat seed = cv::Mat::zeros(box.size(), CV_8UC1);
  for (const int index : region.indices)
  {
    const int pixel = source_pixels[index];
    const cv::Point centre(pixel % width - box.x, pixel / width - box.y);
    cv::rectangle(seed, cv::Rect(centre.x - stride / 2, centre.y - stride / 2, stride, stride), cv::Scalar(255), cv::FILLED);
  }

  Segment segment;
  segment.bounding_box_px = box;
  cv::Mat mask = seed;
  if (params.regrow_footprint)
  {
    pcl::PointCloud<pcl::PointXYZ> region_points(strided, region.indices);
    const PlaneFit plane = fitPlane(region_points);
    if (plane.valid)
    {
      cv::Mat on_plane = cv::Mat::zeros(box.size(), CV_8UC1);
      for (int v = box.y; v < box.y + box.height; ++v)
      {
        const float* depth_row = frame.depth_m.ptr<float>(v);
        std::uint8_t* out = on_plane.ptr<std::uint8_t>(v - box.y);
        for (int u = box.x; u < box.x + box.width; ++u)
        {
          const float z = depth_row[u];
          if (std::isnan(z)) continue;
          const Eigen::Vector3d point = frame.camera.backProject(u, v, z);
          if (std::abs(plane.signedDistance(point)) <= params.footprint_plane_distance_m) out[u - box.x] = 255;
        }
      }
      // Small holes (no depth) inside the face belong to it.
      cv::morphologyEx(on_plane, on_plane, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, {5, 5}));
      cv::Mat labels;
      const int label_count = cv::connectedComponents(on_plane, labels, 8, CV_32S);
      std::vector<int> overlap(static_cast<std::size_t>(label_count), 0);
      for (int v = 0; v < box.height; ++v)
        for (int u = 0; u < box.width; ++u)
          if (seed.at<std::uint8_t>(v, u) && labels.at<int>(v, u) > 0) ++overlap[labels.at<int>(v, u)];
      const auto best = std::max_element(overlap.begin() + 1, overlap.end());
      if (label_count > 1 && *best > 0)
        mask = labels == static_cast<int>(best - overlap.begin());
    }
  }

  segment.mask = mask;
  segment.area_px = cv::countNonZero(mask);
  for (int v = 0; v < box.height; ++v)
  {
    const std::uint8_t* mask_row = mask.ptr<std::uint8_t>(v);
    const float* depth_row = frame.depth_m.ptr<float>(v + box.y);
    for (int u = 0; u < box.width; ++u)
      if (mask_row[u] && !std::isnan(depth_row[u + box.x])) segment.pixel_indices.push_back((v + box.y) * width + u + box.x);
  }
  return segment;
}
/// Number of image pixels two footprints share.
int overlapPx(const Segment& a, const Segment& b)
{
  const cv::Rect common = a.bounding_box_px & b.bounding_box_px;
  if (common.empty()) return 0;
  const cv::Mat a_part = a.mask(common - a.bounding_box_px.tl());
  const cv::Mat b_part = b.mask(common - b.bounding_box_px.tl());
  return cv::countNonZero(a_part & b_part);
}
}  // namespace

void RegionGrowingParams::validate() const
{
  require(stride_px >= 1, "stride_px", "must be >= 1");
  require(normal_smoothing_size > 0.0, "normal_smoothing_size", "must be > 0");
  require(max_depth_change_factor > 0.0, "max_depth_change_factor", "must be > 0");
  require(neighbours >= 3, "neighbours", "must be >= 3");
  require(smoothness_threshold_deg > 0.0 && smoothness_threshold_deg < 90.0, "smoothness_threshold_deg", "must be in (0, 90)");
  require(curvature_threshold > 0.0, "curvature_threshold", "must be > 0");
  require(min_region_points >= 3, "min_region_points", "must be >= 3");
  require(footprint_plane_distance_m > 0.0, "footprint_plane_distance_m", "must be > 0");
  require(min_area_px >= 1, "min_area_px", "must be >= 1");
  require(max_footprint_overlap > 0.0 && max_footprint_overlap <= 1.0, "max_footprint_overlap", "must be in (0, 1]");
}

RegionGrowingSegmenter::RegionGrowingSegmenter(const RegionGrowingParams& params) : params_(params) { params_.validate(); }

std::vector<Segment> RegionGrowingSegmenter::segment(const RgbdFrame& frame) const
{
  std::vector<int> source_pixels;
  const pcl::PointCloud<pcl::PointXYZ>::Ptr strided = makeStridedCloud(frame, params_.stride_px, source_pixels);

  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> normal_estimation;
  normal_estimation.setNormalEstimationMethod(normal_estimation.COVARIANCE_MATRIX);
  normal_estimation.setMaxDepthChangeFactor(static_cast<float>(params_.max_depth_change_factor));
  normal_estimation.setNormalSmoothingSize(static_cast<float>(params_.normal_smoothing_size));
  normal_estimation.setInputCloud(strided);
  normal_estimation.compute(*normals);

  // Region growing needs finite points and normals.
  pcl::IndicesPtr valid(new pcl::Indices);
  for (std::size_t i = 0; i < strided->size(); ++i)
  {
    const pcl::Normal& n = (*normals)[i];
    if (std::isfinite((*strided)[i].z) && std::isfinite(n.normal_x) && std::isfinite(n.curvature))
      valid->push_back(static_cast<int>(i));
  }
  if (static_cast<int>(valid->size()) < params_.min_region_points) return {};

  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::RegionGrowing<pcl::PointXYZ, pcl::Normal> region_growing;
  region_growing.setMinClusterSize(params_.min_region_points);
  region_growing.setMaxClusterSize(static_cast<int>(strided->size()));
  region_growing.setSearchMethod(tree);
  region_growing.setNumberOfNeighbours(params_.neighbours);
  region_growing.setInputCloud(strided);
  region_growing.setIndices(valid);
  region_growing.setInputNormals(normals);
  region_growing.setSmoothnessThreshold(static_cast<float>(params_.smoothness_threshold_deg * kPi / 180.0));
  region_growing.setCurvatureThreshold(static_cast<float>(params_.curvature_threshold));
  std::vector<pcl::PointIndices> regions;
  region_growing.extract(regions);

  std::vector<Segment> footprints;
  for (const pcl::PointIndices& region : regions)
  {
    Segment segment = footprint(frame, *strided, source_pixels, region, params_);
    if (segment.area_px >= params_.min_area_px) footprints.push_back(std::move(segment));
  }
  std::sort(footprints.begin(), footprints.end(), [](const Segment& a, const Segment& b) { return a.area_px > b.area_px; });

  // A face split into several regions regrows into the same footprint
  // several times: keep the largest of overlapping footprints.
  std::vector<Segment> segments;
  for (Segment& candidate : footprints)
  {
    const bool duplicate = std::any_of(segments.begin(), segments.end(), [&](const Segment& kept) {
      return overlapPx(candidate, kept) > params_.max_footprint_overlap * candidate.area_px;
    });
    if (!duplicate) segments.push_back(std::move(candidate));
  }
  return segments;
}
}  // namespace brick_pose
