#pragma once
// The cloud representation the registration core works on: plain Eigen
// points with optional per-point normals. PCL clouds are converted once at the
// API boundary so the algorithms stay free of PCL templates.

#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace brick_pose
{
namespace registration
{
/// Points in metres, with normals either empty or one unit vector per point.
struct PointSet
{
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> normals;

  std::size_t size() const { return points.size(); }
  bool empty() const { return points.empty(); }
  bool hasNormals() const { return !normals.empty(); }

  /// The subset at `indices` (normals follow the points when present).
  PointSet subset(const std::vector<int>& indices) const;
};

PointSet fromPcl(const pcl::PointCloud<pcl::PointXYZ>& cloud);
/// Normals are taken as given; NaN normals are reported by the validation.
PointSet fromPcl(const pcl::PointCloud<pcl::PointNormal>& cloud);
/// Points from `cloud`, normals from `normals` (which must have the same size).
PointSet fromPcl(const pcl::PointCloud<pcl::PointXYZ>& cloud, const pcl::PointCloud<pcl::Normal>& normals);

pcl::PointCloud<pcl::PointXYZ> toPclXyz(const PointSet& set);
/// Normals are zero when `set` has none.
pcl::PointCloud<pcl::PointNormal> toPclPointNormal(const PointSet& set);
}  // namespace registration
}  // namespace brick_pose
