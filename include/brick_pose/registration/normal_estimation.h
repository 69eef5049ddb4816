#pragma once
// Surface normals from local neighbourhoods, for clouds that come without
// them (the ICP refinement needs source normals for its point-to-plane part).

#include <vector>

#include <Eigen/Core>

namespace brick_pose
{
namespace registration
{
/// Unit normal of every point: the least-variance direction of the points
/// within radius_m (PCA). The sign is arbitrary. Points with fewer than 3
/// neighbours get a zero normal.
std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, double radius_m);
}  // namespace registration
}  // namespace brick_pose
