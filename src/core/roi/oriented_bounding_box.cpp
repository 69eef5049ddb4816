#include "brick_pose/roi/oriented_bounding_box.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include <Eigen/Eigenvalues>

namespace brick_pose
{
OrientedBoundingBox computeOrientedBoundingBox(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  OrientedBoundingBox box;
  std::vector<Eigen::Vector3d> points;
  points.reserve(cloud.size());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& point : cloud)
  {
    if (!std::isfinite(point.x) || !std::isfinite(point.y) || !std::isfinite(point.z)) continue;
    points.emplace_back(point.x, point.y, point.z);
    sum += points.back();
  }
  if (points.size() < 3) return box;
  const Eigen::Vector3d mean = sum / static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const auto& point : points) covariance.noalias() += (point - mean) * (point - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  // Eigen sorts eigenvalues ascending: reverse so that column 0 is the major axis.
  Eigen::Matrix3d axes;
  axes.col(0) = solver.eigenvectors().col(2);
  axes.col(1) = solver.eigenvectors().col(1);
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();

  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d high = -low;
  for (const auto& point : points)
  {
    const Eigen::Vector3d local = axes.transpose() * (point - mean);
    low = low.cwiseMin(local);
    high = high.cwiseMax(local);
  }
  box.axes = axes;
  box.extents_m = high - low;
  box.center_m = mean + axes * (0.5 * (low + high));
  box.valid = true;
  return box;
}

std::optional<std::string> checkTopFaceDimensions(double length_m, double width_m, double thickness_m,
                                                  const BrickType& type, const DimensionTolerance& tolerance)
{
  auto describe = [](const char* what, double value_m, const char* rule, double limit_m) {
    std::ostringstream text;
    text.precision(3);
    text << what << " " << value_m << " m " << rule << " " << limit_m << " m";
    return text.str();
  };
  if (thickness_m > tolerance.max_thickness_m)
    return describe("thickness", thickness_m, "exceeds", tolerance.max_thickness_m);
  if (length_m > type.length_m + tolerance.tolerance_m)
    return describe("length", length_m, "exceeds", type.length_m + tolerance.tolerance_m);
  if (width_m > type.width_m + tolerance.tolerance_m)
    return describe("width", width_m, "exceeds", type.width_m + tolerance.tolerance_m);
  const double min_length_m = tolerance.min_visible_fraction * type.length_m - tolerance.tolerance_m;
  const double min_width_m = tolerance.min_visible_fraction * type.width_m - tolerance.tolerance_m;
  if (length_m < min_length_m) return describe("length", length_m, "is below", min_length_m);
  if (width_m < min_width_m) return describe("width", width_m, "is below", min_width_m);
  return std::nullopt;
}
}  // namespace brick_pose
