#include "brick_pose/registration/normal_estimation.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "brick_pose/registration/point_grid.h"

namespace brick_pose
{
namespace registration
{
namespace
{
/// Calls on_normal(i, normal, surface_variation) for every point with at
/// least 3 neighbours within radius_m.
template <typename OnNormal>
void forEachLocalPlane(const std::vector<Eigen::Vector3d>& points, double radius_m, OnNormal&& on_normal)
{
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
    const double total = solver.eigenvalues().sum();
    on_normal(i, Eigen::Vector3d(solver.eigenvectors().col(0)),
              total > 0.0 ? std::max(0.0, solver.eigenvalues()(0)) / total : 1.0);
  }
}
}  // namespace

std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, double radius_m)
{
  std::vector<Eigen::Vector3d> normals(points.size(), Eigen::Vector3d::Zero());
  forEachLocalPlane(points, radius_m,
                    [&](std::size_t i, const Eigen::Vector3d& normal, double) { normals[i] = normal; });
  return normals;
}

ViewNormals estimateViewNormals(const std::vector<Eigen::Vector3d>& points, double radius_m,
                                const Eigen::Vector3d& viewpoint)
{
  ViewNormals result;
  result.normals.assign(points.size(), Eigen::Vector3d::Zero());
  result.surface_variation.assign(points.size(), 1.0);
  forEachLocalPlane(points, radius_m, [&](std::size_t i, const Eigen::Vector3d& normal, double variation) {
    result.normals[i] = normal.dot(viewpoint - points[i]) < 0.0 ? Eigen::Vector3d(-normal) : normal;
    result.surface_variation[i] = variation;
  });
  return result;
}

std::vector<Eigen::Vector3d> estimateOutwardNormals(const std::vector<Eigen::Vector3d>& points, double radius_m)
{
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points)
    centroid += p;
  if (!points.empty())
    centroid /= static_cast<double>(points.size());
  std::vector<Eigen::Vector3d> normals = estimateNormals(points, radius_m);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (normals[i].dot(points[i] - centroid) < 0.0)
      normals[i] = -normals[i];
  return normals;
}
}  // namespace registration
}  // namespace brick_pose
