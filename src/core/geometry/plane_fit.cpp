#include "brick_pose/geometry/plane_fit.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

namespace brick_pose
{
namespace
{
/// Plane through the selected points (all when `keep` is empty).
PlaneFit fitSelected(const std::vector<Eigen::Vector3d>& points, const std::vector<unsigned char>& keep)
{
  PlaneFit plane;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  std::size_t count = 0;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (keep.empty() || keep[i]) { sum += points[i]; ++count; }
  if (count < 3) return plane;
  const Eigen::Vector3d centroid = sum / static_cast<double>(count);
  // The six distinct sums of the symmetric covariance (the same products,
  // added in the same order, as the full outer product's).
  double xx = 0.0, xy = 0.0, xz = 0.0, yy = 0.0, yz = 0.0, zz = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!keep.empty() && !keep[i]) continue;
    const Eigen::Vector3d d = points[i] - centroid;
    xx += d.x() * d.x();
    xy += d.x() * d.y();
    xz += d.x() * d.z();
    yy += d.y() * d.y();
    yz += d.y() * d.z();
    zz += d.z() * d.z();
  }
  Eigen::Matrix3d covariance;
  covariance << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  covariance /= static_cast<double>(count);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  // Collinear points have two vanishing eigenvalues: no unique plane.
  if (solver.eigenvalues()(1) <= 1e-12) return plane;
  Eigen::Vector3d normal = solver.eigenvectors().col(0).normalized();
  if (normal.dot(centroid) > 0.0) normal = -normal;  // face the camera at the origin
  plane.centroid_m = centroid;
  plane.normal = normal;
  plane.rms_m = std::sqrt(std::max(0.0, solver.eigenvalues()(0)));
  plane.inlier_count = count;
  plane.valid = true;
  return plane;
}
}  // namespace

bool PlaneFit::intersectRay(const Eigen::Vector3d& ray, Eigen::Vector3d& hit_m) const
{
  const double denominator = normal.dot(ray);
  if (std::abs(denominator) < 1e-9) return false;
  const double scale = normal.dot(centroid_m) / denominator;
  if (!(scale > 0.0)) return false;
  hit_m = scale * ray;
  return true;
}

PlaneFit fitPlane(const pcl::PointCloud<pcl::PointXYZ>& cloud, const PlaneFitParams& params)
{
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  for (const auto& point : cloud)
    if (std::isfinite(point.x) && std::isfinite(point.y) && std::isfinite(point.z))
      points.emplace_back(point.x, point.y, point.z);

  PlaneFit plane = fitSelected(points, {});
  std::vector<double> residuals(points.size());
  std::vector<unsigned char> keep(points.size());
  for (int iteration = 0; plane.valid && iteration < params.refit_iterations; ++iteration)
  {
    for (std::size_t i = 0; i < points.size(); ++i) residuals[i] = std::abs(plane.signedDistance(points[i]));
    std::vector<double> sorted = residuals;
    auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
    std::nth_element(sorted.begin(), middle, sorted.end());  // linear time
    const double threshold = std::max(params.min_inlier_distance_m, params.mad_factor * 1.4826 * *middle);
    for (std::size_t i = 0; i < points.size(); ++i) keep[i] = residuals[i] <= threshold;
    const PlaneFit refit = fitSelected(points, keep);
    if (!refit.valid) break;
    plane = refit;
  }
  return plane;
}
}  // namespace brick_pose
