#pragma once
// The paper's point cloud processing (section "Sensor data processing"):
// passthrough crop on depth, statistical outlier removal, voxel grid
// downsampling and moving-least-squares smoothing with normals. Every step is
// switchable; the front end runs them on small segment clouds only.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace brick_pose
{
struct CloudProcessorParams
{
  /// Passthrough on z. The D415 measures from ~0.3 m; beyond ~3 m its depth
  /// noise (~1% of range and growing with its square) is too large for plates.
  bool crop_enabled = true;
  double min_depth_m = 0.3;
  double max_depth_m = 3.0;

  /// Statistical outlier removal: drops points whose mean distance to their
  /// k nearest neighbours is more than stddev_multiplier sigmas above the mean.
  bool outlier_removal_enabled = true;
  int outlier_mean_k = 16;
  double outlier_stddev_multiplier = 2.0;

  /// Voxel grid: one point (the centroid) per leaf_m cube.
  bool voxel_enabled = true;
  double voxel_leaf_m = 0.005;

  /// Moving least squares: local polynomial fit within search_radius_m,
  /// producing smoothed points with normals.
  bool mls_enabled = false;
  double mls_search_radius_m = 0.02;
  int mls_polynomial_order = 2;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// Milliseconds spent in each step of one process() call (0 when skipped).
struct CloudProcessingTimings
{
  double crop_ms = 0.0;
  double outlier_removal_ms = 0.0;
  double voxel_ms = 0.0;
  double mls_ms = 0.0;
  double total() const { return crop_ms + outlier_removal_ms + voxel_ms + mls_ms; }
  /// Step by step: the times of several clouds (or frames) summed.
  CloudProcessingTimings& operator+=(const CloudProcessingTimings& other);
  /// Every step times `factor` (a share of overlapping threads' wall time).
  CloudProcessingTimings scaled(double factor) const;
};

/// Result of the enabled steps.
struct ProcessedCloud
{
  pcl::PointCloud<pcl::PointXYZ>::Ptr points;          ///< After crop/SOR/voxel (and MLS, when enabled).
  pcl::PointCloud<pcl::PointNormal>::Ptr with_normals; ///< MLS output; null when MLS is off.
  CloudProcessingTimings timings;
};

class CloudProcessor
{
public:
  explicit CloudProcessor(const CloudProcessorParams& params = CloudProcessorParams());

  /// Runs the enabled steps: crop, voxel grid, outlier removal, MLS (voxel
  /// before SOR: the k-NN statistics are cheaper on the thinned cloud). The
  /// input is not modified.
  ProcessedCloud process(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const;

  /// Keeps points with min_depth_m <= z <= max_depth_m (drops NaN points).
  pcl::PointCloud<pcl::PointXYZ>::Ptr crop(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const;
  /// Same on an organised colour cloud; keeps it organised (cut points become NaN).
  pcl::PointCloud<pcl::PointXYZRGB>::Ptr cropOrganized(const pcl::PointCloud<pcl::PointXYZRGB>::ConstPtr& cloud) const;
  pcl::PointCloud<pcl::PointXYZ>::Ptr removeOutliers(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const;
  pcl::PointCloud<pcl::PointXYZ>::Ptr downsample(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const;
  pcl::PointCloud<pcl::PointNormal>::Ptr smooth(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud) const;

  const CloudProcessorParams& params() const { return params_; }

private:
  CloudProcessorParams params_;
};
}  // namespace brick_pose
