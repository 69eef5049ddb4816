#include "brick_pose/registration/point_set.h"

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace registration
{
PointSet PointSet::subset(const std::vector<int>& indices) const
{
  PointSet out;
  out.points.reserve(indices.size());
  for (int i : indices)
    out.points.push_back(points[i]);
  if (hasNormals())
  {
    out.normals.reserve(indices.size());
    for (int i : indices)
      out.normals.push_back(normals[i]);
  }
  return out;
}

PointSet fromPcl(const pcl::PointCloud<pcl::PointXYZ>& cloud)
{
  PointSet set;
  set.points.reserve(cloud.size());
  for (const auto& p : cloud.points)
    set.points.emplace_back(p.x, p.y, p.z);
  return set;
}

PointSet fromPcl(const pcl::PointCloud<pcl::PointNormal>& cloud)
{
  PointSet set;
  set.points.reserve(cloud.size());
  set.normals.reserve(cloud.size());
  for (const auto& p : cloud.points)
  {
    set.points.emplace_back(p.x, p.y, p.z);
    set.normals.emplace_back(p.normal_x, p.normal_y, p.normal_z);
  }
  return set;
}

PointSet fromPcl(const pcl::PointCloud<pcl::PointXYZ>& cloud, const pcl::PointCloud<pcl::Normal>& normals)
{
  if (normals.size() != cloud.size())
    throw InputError("normals cloud has " + std::to_string(normals.size()) + " normals for " +
                     std::to_string(cloud.size()) + " points");
  PointSet set = fromPcl(cloud);
  set.normals.reserve(normals.size());
  for (const auto& n : normals.points)
    set.normals.emplace_back(n.normal_x, n.normal_y, n.normal_z);
  return set;
}

pcl::PointCloud<pcl::PointXYZ> toPclXyz(const PointSet& set)
{
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.reserve(set.size());
  for (const Eigen::Vector3d& p : set.points)
    cloud.push_back(pcl::PointXYZ(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())));
  return cloud;
}

pcl::PointCloud<pcl::PointNormal> toPclPointNormal(const PointSet& set)
{
  pcl::PointCloud<pcl::PointNormal> cloud;
  cloud.reserve(set.size());
  for (std::size_t i = 0; i < set.size(); ++i)
  {
    const Eigen::Vector3f point = set.points[i].cast<float>();
    const Eigen::Vector3f normal = set.hasNormals() ? Eigen::Vector3f(set.normals[i].cast<float>()) : Eigen::Vector3f::Zero();
    pcl::PointNormal p;
    p.x = point.x();
    p.y = point.y();
    p.z = point.z();
    p.normal_x = normal.x();
    p.normal_y = normal.y();
    p.normal_z = normal.z();
    p.curvature = 0.0f;
    cloud.push_back(p);
  }
  return cloud;
}
}  // namespace registration
}  // namespace brick_pose
