#pragma once
// Least-squares plane of a segment in linear time: covariance of the points,
// normal = eigenvector of the smallest eigenvalue, with a robust refit that
// drops points far from the first plane (flying pixels at the plate border).

#include <cstddef>

#include <Eigen/Core>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace brick_pose
{
struct PlaneFitParams
{
  /// Refits after dropping points farther than max(min_inlier_distance_m,
  /// mad_factor * 1.4826 * MAD of the residuals) from the previous plane.
  int refit_iterations = 2;
  double mad_factor = 3.0;
  double min_inlier_distance_m = 0.004;
};

struct PlaneFit
{
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  /// Unit normal, oriented toward the camera (normal . centroid < 0).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double rms_m = 0.0;  ///< RMS point-to-plane distance of the inliers.
  std::size_t inlier_count = 0;
  bool valid = false;  ///< False when there were fewer than 3 points or they were collinear.

  double signedDistance(const Eigen::Vector3d& point_m) const { return normal.dot(point_m - centroid_m); }

  /// Intersection of the camera ray (z = 1 direction) with the plane; false
  /// when the ray is parallel to the plane or the hit is behind the camera.
  bool intersectRay(const Eigen::Vector3d& ray, Eigen::Vector3d& hit_m) const;
};

/// Fits a plane to all finite points of `cloud`.
PlaneFit fitPlane(const pcl::PointCloud<pcl::PointXYZ>& cloud, const PlaneFitParams& params = PlaneFitParams());
}  // namespace brick_pose
