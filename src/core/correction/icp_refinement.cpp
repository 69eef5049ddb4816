#include "brick_pose/correction/icp_refinement.h"

#include <cmath>
#include <string>

#include <pcl/filters/filter.h>
#include <pcl/registration/icp.h>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
using Cloud = pcl::PointCloud<pcl::PointXYZ>;

bool isPositiveFinite(double value)
{
  return std::isfinite(value) && value > 0.0;
}

/// Points on the top face of `brick` in the brick frame (z = 0), on a grid
/// that includes the edges: the edges are what pin yaw and in-plane position
/// for ICP on a planar face. Local stand-in until the registration stage
/// offers a shared model-cloud sampler.
Cloud::Ptr sampleTopFace(const BrickType& brick, double spacing_m)
{
  const int columns = static_cast<int>(std::ceil(brick.length_m / spacing_m)) + 1;
  const int rows = static_cast<int>(std::ceil(brick.width_m / spacing_m)) + 1;
  Cloud::Ptr model(new Cloud);
  model->reserve(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows));
  for (int column = 0; column < columns; ++column)
  {
    const double x_m = brick.length_m * (static_cast<double>(column) / (columns - 1) - 0.5);
    for (int row = 0; row < rows; ++row)
    {
      const double y_m = brick.width_m * (static_cast<double>(row) / (rows - 1) - 0.5);
      model->push_back(pcl::PointXYZ(static_cast<float>(x_m), static_cast<float>(y_m), 0.0f));
    }
  }
  return model;
}

/// PCL works in float; snap the result back to an exact rotation.
Eigen::Isometry3d toIsometry(const Eigen::Matrix4f& transform)
{
  const Eigen::Matrix4d matrix = transform.cast<double>();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = Eigen::Quaterniond(Eigen::Matrix3d(matrix.topLeftCorner<3, 3>())).normalized().toRotationMatrix();
  pose.translation() = matrix.topRightCorner<3, 1>();
  return pose;
}
}  // namespace

void IcpParams::validate() const
{
  if (!isPositiveFinite(max_correspondence_distance_m))
    throw ConfigError("icp: max_correspondence_distance_m must be positive");
  if (max_iterations < 1)
    throw ConfigError("icp: max_iterations must be at least 1");
  if (!(std::isfinite(transformation_epsilon_m2) && transformation_epsilon_m2 >= 0.0))
    throw ConfigError("icp: transformation_epsilon_m2 must be finite and not negative");
  if (!(std::isfinite(relative_fitness_epsilon) && relative_fitness_epsilon >= 0.0))
    throw ConfigError("icp: relative_fitness_epsilon must be finite and not negative");
  if (!isPositiveFinite(model_spacing_m))
    throw ConfigError("icp: model_spacing_m must be positive");
  if (max_target_points < 3) throw ConfigError("icp: max_target_points must be >= 3");
}

/// At most about `max_points` of `cloud`, taken at a fixed stride. The
/// segment is an organised scan, so a stride spreads the kept points evenly.
Cloud::Ptr everyNth(const Cloud& cloud, int max_points)
{
  const std::size_t stride = (cloud.size() + max_points - 1) / static_cast<std::size_t>(max_points);
  if (stride <= 1) return Cloud::Ptr(new Cloud(cloud));
  Cloud::Ptr kept(new Cloud);
  for (std::size_t i = 0; i < cloud.size(); i += stride)
    kept->push_back(cloud[i]);
  return kept;
}

IcpRefinement refinePoseWithIcp(const Eigen::Isometry3d& initial_pose, const BrickType& brick,
                                const pcl::PointCloud<pcl::PointXYZ>& segment_cloud, const IcpParams& parameters)
{
  parameters.validate();
  if (!isPositiveFinite(brick.length_m) || !isPositiveFinite(brick.width_m))
    throw ConfigError("icp: brick '" + brick.name + "' needs a positive length_m and width_m");
  if (!initial_pose.matrix().allFinite())
    throw InputError("icp: initial pose is not finite (NaN or Inf)");

  Cloud::Ptr target(new Cloud);
  pcl::Indices kept;
  pcl::removeNaNFromPointCloud(segment_cloud, *target, kept);
  if (target->size() < 3)
    throw InputError("icp: the segment cloud has " + std::to_string(target->size()) +
                     " finite points, at least 3 are needed");

  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setInputSource(sampleTopFace(brick, parameters.model_spacing_m));
  icp.setInputTarget(everyNth(*target, parameters.max_target_points));
  icp.setMaxCorrespondenceDistance(parameters.max_correspondence_distance_m);
  icp.setMaximumIterations(parameters.max_iterations);
  icp.setTransformationEpsilon(parameters.transformation_epsilon_m2);
  icp.setEuclideanFitnessEpsilon(parameters.relative_fitness_epsilon);

  Cloud aligned;
  icp.align(aligned, initial_pose.matrix().cast<float>());

  IcpRefinement result;
  result.converged = icp.hasConverged();
  result.refined_pose = result.converged ? toIsometry(icp.getFinalTransformation()) : initial_pose;
  result.fitness_m2 = icp.getFitnessScore(parameters.max_correspondence_distance_m);
  return result;
}
}  // namespace brick_pose
