#include "brick_pose/registration/normal_estimation.h"

#include <Eigen/Eigenvalues>

#include "brick_pose/registration/point_grid.h"

namespace brick_pose
{
namespace registration
{
std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, double radius_m)
{
  std::vector<Eigen::Vector3d> normals(points.size(), Eigen::Vector3d::Zero());
  const PointGrid grid(points, radius_m);
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d sum_outer = Eigen::Matrix3d::Zero();
    int count = 0;
    grid.forEachWithin(points[i], radius_m, [&](int j) {
      const Eigen::Vector3d d = points[j] - points[i];  // centred on i for precision
      sum += d;
      sum_outer += d * d.transpose();
      ++count;
    });
    if (count < 3)
      continue;
    const Eigen::Vector3d mean = sum / count;
    const Eigen::Matrix3d covariance = sum_outer / count - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
    normals[i] = solver.eigenvectors().col(0);
  }
  return normals;
}
}  // namespace registration
}  // namespace brick_pose
