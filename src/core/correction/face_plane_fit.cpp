#include "brick_pose/correction/face_plane_fit.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Eigenvalues>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace correction
{
namespace
{
// The middle eigenvalue of the covariance relative to the largest: below this
// the points lie on a line and every plane through it fits equally well.
constexpr double kCollinearRatio = 1e-10;

bool isFinite(const pcl::PointXYZ& point)
{
  return std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.z);
}
}  // namespace

FittedPlane fitPlaneTowardCamera(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  // Two passes (mean, then covariance about it) keep the covariance exact for
  // faces a metre from the camera, where a one-pass sum would cancel badly.
  FittedPlane plane;
  Eigen::Vector3d sum_m = Eigen::Vector3d::Zero();
  for (const pcl::PointXYZ& point : cloud.points)
  {
    if (!isFinite(point))
      continue;
    sum_m += point.getVector3fMap().cast<double>();
    ++plane.point_count;
  }
  if (plane.point_count < 3)
    throw InputError("face plane fit: " + std::to_string(plane.point_count) +
                     " finite points, at least 3 are needed");
  plane.centroid_m = sum_m / static_cast<double>(plane.point_count);

  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const pcl::PointXYZ& point : cloud.points)
  {
    if (!isFinite(point))
      continue;
    const Eigen::Vector3d centred = point.getVector3fMap().cast<double>() - plane.centroid_m;
    covariance += centred * centred.transpose();
  }
  covariance /= static_cast<double>(plane.point_count);

  // Eigenvalues come sorted in increasing order.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d eigenvalues = solver.eigenvalues();
  if (!(eigenvalues(1) > kCollinearRatio * eigenvalues(2)))
    throw InputError("face plane fit: the points are collinear (or identical); no plane is defined");
  plane.normal = solver.eigenvectors().col(0).normalized();
  if (plane.normal.dot(plane.centroid_m) > 0.0)
    plane.normal = -plane.normal;  // the camera sits at the origin
  plane.rms_distance_m = std::sqrt(std::max(0.0, eigenvalues(0)));
  return plane;
}
}  // namespace correction
}  // namespace brick_pose
