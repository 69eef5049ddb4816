#pragma once
// Least-squares plane of a face segment, for building a MeasuredFace where the
// front end supplies no normal. Kept in brick_pose::correction so that it does
// not clash with the front end's own plane fit.

#include <cstddef>

#include <Eigen/Core>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace brick_pose
{
namespace correction
{
/// A plane through `centroid_m` with unit `normal`, in the cloud's frame.
struct FittedPlane
{
  Eigen::Vector3d centroid_m = Eigen::Vector3d::Zero();
  /// Unit normal, oriented toward the origin of the cloud's frame (the camera).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  /// Root mean square distance of the points from the plane.
  double rms_distance_m = 0.0;
  std::size_t point_count = 0;
};

/// Total least squares: the normal is the eigenvector of the smallest
/// eigenvalue of the points' 3x3 covariance. Non-finite points are skipped.
/// Throws InputError for fewer than 3 finite points or collinear points.
FittedPlane fitPlaneTowardCamera(const pcl::PointCloud<pcl::PointXYZ>& cloud);
}  // namespace correction
}  // namespace brick_pose
