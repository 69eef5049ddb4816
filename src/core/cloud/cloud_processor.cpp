// All PCL filter templates the package uses are instantiated here, on point
// types PCL precompiles, so that only this file pays PCL's compile time.
#include "brick_pose/cloud/cloud_processor.h"

#include <chrono>
#include <cmath>

#include <pcl/common/io.h>
#include <pcl/filters/passthrough.h>
#include <pcl/filters/statistical_outlier_removal.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include "brick_pose/common/elapsed.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
}  // namespace

void CloudProcessorParams::validate() const
{
  const ParamCheck check("cloud processing");
  check.require(std::isfinite(min_depth_m) && min_depth_m >= 0.0, "min_depth_m", "must be >= 0");
  check.require(std::isfinite(max_depth_m) && max_depth_m > min_depth_m, "max_depth_m", "must be > min_depth_m");
  check.require(outlier_mean_k >= 1, "outlier_mean_k", "must be >= 1");
  check.require(outlier_stddev_multiplier > 0.0, "outlier_stddev_multiplier", "must be > 0");
  check.require(voxel_leaf_m > 0.0, "voxel_leaf_m", "must be > 0");
  check.require(mls_search_radius_m > 0.0, "mls_search_radius_m", "must be > 0");
  check.require(mls_polynomial_order >= 0 && mls_polynomial_order <= 3, "mls_polynomial_order", "must be 0..3");
}

CloudProcessingTimings& CloudProcessingTimings::operator+=(const CloudProcessingTimings& other)
{
  crop_ms += other.crop_ms;
  outlier_removal_ms += other.outlier_removal_ms;
  voxel_ms += other.voxel_ms;
  mls_ms += other.mls_ms;
  return *this;
}

CloudProcessingTimings CloudProcessingTimings::scaled(double factor) const
{
  return {crop_ms * factor, outlier_removal_ms * factor, voxel_ms * factor, mls_ms * factor};
}

CloudProcessor::CloudProcessor(const CloudProcessorParams& params) : params_(params) { params_.validate(); }

pcl::PointCloud<pcl::PointXYZ>::Ptr CloudProcessor::crop(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr cropped(new pcl::PointCloud<pcl::PointXYZ>);
  pcl::PassThrough<pcl::PointXYZ> passthrough;
  passthrough.setInputCloud(cloud);
  passthrough.setFilterFieldName("z");
  passthrough.setFilterLimits(static_cast<float>(params_.min_depth_m), static_cast<float>(params_.max_depth_m));
  passthrough.filter(*cropped);
  return cropped;
}

pcl::PointCloud<pcl::PointXYZRGB>::Ptr CloudProcessor::cropOrganized(
    const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr& cloud) const
{
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr cropped(new pcl::PointCloud<pcl::PointXYZRGB>);
  pcl::PassThrough<pcl::PointXYZRGB> passthrough(true);  // keeping organised needs the removed indices
  passthrough.setInputCloud(cloud);
  passthrough.setFilterFieldName("z");
  passthrough.setFilterLimits(static_cast<float>(params_.min_depth_m), static_cast<float>(params_.max_depth_m));
  passthrough.setKeepOrganized(true);
  passthrough.filter(*cropped);
  return cropped;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr CloudProcessor::removeOutliers(
    const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr kept(new pcl::PointCloud<pcl::PointXYZ>);
  if (static_cast<int>(cloud->size()) <= params_.outlier_mean_k)
  {
    *kept = *cloud;  // too few points for the statistics to mean anything
    return kept;
  }
  pcl::StatisticalOutlierRemoval<pcl::PointXYZ> outlier_removal;
  outlier_removal.setInputCloud(cloud);
  outlier_removal.setMeanK(params_.outlier_mean_k);
  outlier_removal.setStddevMulThresh(params_.outlier_stddev_multiplier);
  outlier_removal.filter(*kept);
  return kept;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr CloudProcessor::downsample(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr downsampled(new pcl::PointCloud<pcl::PointXYZ>);
  pcl::VoxelGrid<pcl::PointXYZ> voxel_grid;
  voxel_grid.setInputCloud(cloud);
  const float leaf = static_cast<float>(params_.voxel_leaf_m);
  voxel_grid.setLeafSize(leaf, leaf, leaf);
  voxel_grid.filter(*downsampled);
  return downsampled;
}

pcl::PointCloud<pcl::PointNormal>::Ptr CloudProcessor::smooth(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const
{
  pcl::PointCloud<pcl::PointNormal>::Ptr smoothed(new pcl::PointCloud<pcl::PointNormal>);
  if (cloud->size() < 3) return smoothed;
  pcl::search::KdTree<pcl::PointXYZ>::Ptr tree(new pcl::search::KdTree<pcl::PointXYZ>);
  pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
  mls.setInputCloud(cloud);
  mls.setSearchMethod(tree);
  mls.setComputeNormals(true);
  mls.setPolynomialOrder(params_.mls_polynomial_order);
  mls.setSearchRadius(params_.mls_search_radius_m);
  mls.process(*smoothed);
  return smoothed;
}

ProcessedCloud CloudProcessor::process(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const
{
  ProcessedCloud result;
  pcl::PointCloud<pcl::PointXYZ>::ConstPtr current = cloud;
  auto start = SteadyClock::now();
  if (params_.crop_enabled)
  {
    current = crop(current);
    result.timings.crop_ms = millisecondsSince(start);
  }
  // The voxel grid runs before outlier removal, unlike the paper: the
  // statistics are the same on the thinned cloud and the k-NN search is far
  // cheaper on it.
  start = SteadyClock::now();
  if (params_.voxel_enabled && !current->empty())
  {
    current = downsample(current);
    result.timings.voxel_ms = millisecondsSince(start);
  }
  start = SteadyClock::now();
  if (params_.outlier_removal_enabled && !current->empty())
  {
    current = removeOutliers(current);
    result.timings.outlier_removal_ms = millisecondsSince(start);
  }
  start = SteadyClock::now();
  if (params_.mls_enabled && !current->empty())
  {
    result.with_normals = smooth(current);
    pcl::PointCloud<pcl::PointXYZ>::Ptr smoothed(new pcl::PointCloud<pcl::PointXYZ>);
    pcl::copyPointCloud(*result.with_normals, *smoothed);
    current = smoothed;
    result.timings.mls_ms = millisecondsSince(start);
  }
  if (current == cloud)
    result.points.reset(new pcl::PointCloud<pcl::PointXYZ>(*cloud));
  else
    result.points = std::const_pointer_cast<pcl::PointCloud<pcl::PointXYZ>>(current);
  return result;
}
}  // namespace brick_pose
