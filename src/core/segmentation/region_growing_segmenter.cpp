// PCL normal estimation and region growing are instantiated here only, on
// PointXYZ/Normal, which PCL precompiles.
#include "brick_pose/segmentation/region_growing_segmenter.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <opencv2/imgproc.hpp>
#include <pcl/features/integral_image_normal.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/region_growing.h>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/frame/organized_cloud.h"
#include "brick_pose/geometry/plane_fit.h"

namespace brick_pose
{
namespace
{

/// Distance from the plane a pixel of depth z may have and still be on it:
/// the configured floor or three sigmas of the sensor's axial noise.
double planeTolerance(const RegionGrowingParams& params, double depth_m)
{
  return std::max(params.footprint_plane_distance_m, 3.0 * params.depth_noise_at_1m_m * depth_m * depth_m);
}

/// Full-resolution footprint of one region: the 4-connected pixels reachable
/// from the region's own pixels over pixels lying on the region's plane and
/// not claimed by an earlier (larger) footprint. Region growing leaves out
/// the border of a face (normals bend there) and may split one face into
/// several regions; the flood fill restores the border and the `claimed`
/// image merges the pieces. Empty when the region's pixels are mostly taken.
std::optional<Segment> floodFootprint(const RgbdFrame& frame, const pcl::PointCloud<pcl::PointXYZ>& strided,
                                      const std::vector<int>& source_pixels, const pcl::PointIndices& region,
                                      const RegionGrowingParams& params, cv::Mat& claimed)
{
  const int width = frame.width_px();
  const int height = frame.height_px();
  std::uint8_t* taken = claimed.ptr<std::uint8_t>(0);
  int already_taken = 0;
  for (const int index : region.indices) already_taken += taken[source_pixels[index]] ? 1 : 0;
  if (already_taken > params.max_footprint_overlap * static_cast<double>(region.indices.size())) return std::nullopt;

  const pcl::PointCloud<pcl::PointXYZ> region_points(strided, region.indices);
  const PlaneFit plane = fitPlane(region_points);
  if (!plane.valid) return std::nullopt;
  const float* depth = frame.depth_m.ptr<float>(0);
  auto onPlane = [&](int pixel) {
    const float z = depth[pixel];
    if (std::isnan(z)) return false;
    const Eigen::Vector3d point = frame.camera.backProject(pixel % width, pixel / width, z);
    return std::abs(plane.signedDistance(point)) <= planeTolerance(params, z);
  };

  std::vector<int> footprint;
  std::vector<int> frontier;
  for (const int index : region.indices)
  {
    const int pixel = source_pixels[index];
    if (taken[pixel] || !onPlane(pixel)) continue;
    taken[pixel] = 255;
    frontier.push_back(pixel);
  }
  while (!frontier.empty())
  {
    const int pixel = frontier.back();
    frontier.pop_back();
    footprint.push_back(pixel);
    const int u = pixel % width, v = pixel / width;
    const int neighbours[4] = {u > 0 ? pixel - 1 : -1, u + 1 < width ? pixel + 1 : -1, v > 0 ? pixel - width : -1,
                               v + 1 < height ? pixel + width : -1};
    for (const int next : neighbours)
      if (next >= 0 && !taken[next] && onPlane(next))
      {
        taken[next] = 255;
        frontier.push_back(next);
      }
  }
  if (static_cast<int>(footprint.size()) < params.min_area_px) return std::nullopt;

  std::sort(footprint.begin(), footprint.end());
  int u_min = width, v_min = height, u_max = 0, v_max = 0;
  for (const int pixel : footprint)
  {
    u_min = std::min(u_min, pixel % width);
    u_max = std::max(u_max, pixel % width);
    v_min = std::min(v_min, pixel / width);
    v_max = std::max(v_max, pixel / width);
  }
  Segment segment;
  segment.bounding_box_px = cv::Rect(cv::Point(u_min, v_min), cv::Point(u_max + 1, v_max + 1));
  segment.mask = cv::Mat::zeros(segment.bounding_box_px.size(), CV_8UC1);
  for (const int pixel : footprint) segment.mask.at<std::uint8_t>(pixel / width - v_min, pixel % width - u_min) = 255;
  // Pixels without depth inside the face (dropouts) belong to its outline.
  cv::morphologyEx(segment.mask, segment.mask, cv::MORPH_CLOSE, cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  segment.area_px = cv::countNonZero(segment.mask);
  segment.pixel_indices = std::move(footprint);
  return segment;
}

}  // namespace

void RegionGrowingParams::validate() const
{
  const ParamCheck check("region growing");
  check.require(block_angle_mrad > 0.0, "block_angle_mrad", "must be > 0");
  check.require(normal_smoothing_size > 0.0, "normal_smoothing_size", "must be > 0");
  check.require(max_depth_change_factor > 0.0, "max_depth_change_factor", "must be > 0");
  check.require(neighbours >= 3, "neighbours", "must be >= 3");
  check.require(smoothness_threshold_deg > 0.0 && smoothness_threshold_deg < 90.0,
                "smoothness_threshold_deg", "must be in (0, 90)");
  check.require(curvature_threshold > 0.0, "curvature_threshold", "must be > 0");
  check.require(min_region_points >= 3, "min_region_points", "must be >= 3");
  check.require(footprint_plane_distance_m > 0.0, "footprint_plane_distance_m", "must be > 0");
  check.require(depth_noise_at_1m_m >= 0.0, "depth_noise_at_1m_m", "must be >= 0");
  check.require(min_area_px >= 1, "min_area_px", "must be >= 1");
  check.require(max_footprint_overlap >= 0.0 && max_footprint_overlap <= 1.0,
                "max_footprint_overlap", "must be in [0, 1]");
}

RegionGrowingSegmenter::RegionGrowingSegmenter(const RegionGrowingParams& params) : params_(params) { params_.validate(); }

int RegionGrowingSegmenter::strideFor(double fx_px, int width_px, int height_px) const
{
  const double stride_px = 1e-3 * params_.block_angle_mrad * fx_px;
  // A focal length far too short for the image (a bad camera_info) must
  // not thin a frame into more blocks than region growing can take.
  const double pixels = static_cast<double>(std::max(0, width_px)) * std::max(0, height_px);
  const int fewest_px = static_cast<int>(std::ceil(std::sqrt(pixels / kMaxBlocks)));
  return std::max({1, fewest_px, std::isfinite(stride_px) ? roundToInt(stride_px) : 1});
}

std::vector<Segment> RegionGrowingSegmenter::segment(const RgbdFrame& frame) const
{
  std::vector<int> source_pixels;
  // Block medians rather than every stride-th pixel: sunlight leaves so many
  // dropouts that the integral-image normals of a strided cloud vanish.
  const pcl::PointCloud<pcl::PointXYZ>::Ptr strided =
      makeBlockMedianCloud(frame, strideFor(frame.camera.fx_px, frame.width_px(), frame.height_px()), source_pixels);
  // PCL's integral-image normals read outside a cloud smaller than their
  // window (and then leave no normals); such a frame holds no plate anyway.
  const auto min_side = static_cast<std::uint32_t>(2.0 * std::ceil(params_.normal_smoothing_size) + 2.0);
  if (strided->width < min_side || strided->height < min_side) return {};

  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::IntegralImageNormalEstimation<pcl::PointXYZ, pcl::Normal> normal_estimation;
  normal_estimation.setNormalEstimationMethod(normal_estimation.COVARIANCE_MATRIX);
  normal_estimation.setMaxDepthChangeFactor(static_cast<float>(params_.max_depth_change_factor));
  normal_estimation.setNormalSmoothingSize(static_cast<float>(params_.normal_smoothing_size));
  normal_estimation.setInputCloud(strided);
  normal_estimation.compute(*normals);
  if (normals->size() != strided->size()) return {};  // PCL gave up on this cloud

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
  region_growing.setSmoothnessThreshold(static_cast<float>(params_.smoothness_threshold_deg * kDegToRad));
  region_growing.setCurvatureThreshold(static_cast<float>(params_.curvature_threshold));
  std::vector<pcl::PointIndices> regions;
  region_growing.extract(regions);

  // Largest regions first, so that a face's biggest piece claims the face.
  std::sort(regions.begin(), regions.end(),
            [](const pcl::PointIndices& a, const pcl::PointIndices& b) { return a.indices.size() > b.indices.size(); });
  cv::Mat claimed = cv::Mat::zeros(frame.depth_m.size(), CV_8UC1);
  std::vector<Segment> segments;
  for (const pcl::PointIndices& region : regions)
    if (std::optional<Segment> segment = floodFootprint(frame, *strided, source_pixels, region, params_, claimed))
      segments.push_back(std::move(*segment));
  std::sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) { return a.area_px > b.area_px; });
  return segments;
}
}  // namespace brick_pose
