#include "brick_pose/registration/input_validation.h"

#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
namespace
{
[[noreturn]] void reject(const std::string& cloud_name, const std::string& problem)
{
  throw InputError(cloud_name + " cloud " + problem);
}

// Far beyond any camera's range; bounding coordinates keeps grid indices exact.
constexpr double kMaxCoordinateM = 1.0e6;

void checkFinite(const PointSet& cloud, const std::string& cloud_name)
{
  for (std::size_t i = 0; i < cloud.size(); ++i)
  {
    if (!cloud.points[i].allFinite())
      reject(cloud_name, "has a NaN/Inf coordinate at point " + std::to_string(i));
    if (cloud.points[i].cwiseAbs().maxCoeff() > kMaxCoordinateM)
      reject(cloud_name, "has a coordinate beyond 1e6 m at point " + std::to_string(i) + " (wrong units?)");
  }
  if (!cloud.hasNormals())
    return;
  if (cloud.normals.size() != cloud.points.size())
    reject(cloud_name, "has " + std::to_string(cloud.normals.size()) + " normals for " + std::to_string(cloud.size()) + " points");
  for (std::size_t i = 0; i < cloud.normals.size(); ++i)
  {
    if (!cloud.normals[i].allFinite())
      reject(cloud_name, "has a NaN/Inf normal at point " + std::to_string(i));
    if (cloud.normals[i].squaredNorm() < 1e-12)
      reject(cloud_name, "has a zero normal at point " + std::to_string(i));
  }
}

// Identical and collinear clouds have a covariance of rank 0 and 1; relative
// thresholds keep the test independent of the units and of the cloud's size.
void checkSpread(const PointSet& cloud, const std::string& cloud_name)
{
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : cloud.points)
    mean += p;
  mean /= static_cast<double>(cloud.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double max_offset = 0.0;
  for (const Eigen::Vector3d& p : cloud.points)
  {
    const Eigen::Vector3d d = p - mean;
    covariance += d * d.transpose();
    max_offset = std::max(max_offset, d.cwiseAbs().maxCoeff());
  }
  covariance /= static_cast<double>(cloud.size());
  const double scale = std::max(1.0, mean.cwiseAbs().maxCoeff());
  if (max_offset <= 1e-9 * scale)
    reject(cloud_name, "has all " + std::to_string(cloud.size()) + " points identical");
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  const Eigen::Vector3d variances = solver.eigenvalues();  // ascending
  if (std::sqrt(std::max(0.0, variances(1))) <= 1e-7 * std::sqrt(variances(2)) + 1e-12 * scale)
    reject(cloud_name, "has all points collinear (no 4-point base exists)");
}
}  // namespace

void validateRegistrationInput(const PointSet& cloud, const std::string& cloud_name)
{
  if (cloud.empty())
    reject(cloud_name, "is empty");
  if (cloud.size() < 4)
    reject(cloud_name, "has " + std::to_string(cloud.size()) + " points, at least 4 are needed");
  checkFinite(cloud, cloud_name);
  checkSpread(cloud, cloud_name);
}
}  // namespace registration
}  // namespace brick_pose
