#pragma once
// Surface normals from local neighbourhoods, for clouds that come without
// them (the ICP refinement needs source normals for its point-to-plane part).

#include <vector>

#include <Eigen/Core>

namespace brick_pose
{
namespace registration
{
/// Neighbourhood radius for normals over a cloud's median sample spacing:
/// about 20 neighbours on an even sample, enough for a stable PCA and small
/// enough that a face's normal holds up to a few spacings from its edges.
constexpr double kNormalRadiusPerSpacing = 2.5;

/// Unit normal of every point: the least-variance direction of the points
/// within radius_m (PCA). The sign is arbitrary. Points with fewer than 3
/// neighbours get a zero normal.
std::vector<Eigen::Vector3d> estimateNormals(const std::vector<Eigen::Vector3d>& points, double radius_m);

/// Normals of a scan seen from one viewpoint, with how far to trust each.
struct ViewNormals
{
  /// Unit, turned towards the viewpoint (a surface is seen from its front);
  /// zero where too few neighbours were found.
  std::vector<Eigen::Vector3d> normals;
  /// Smallest eigenvalue of the neighbourhood covariance over their sum: about
  /// 0 on a flat patch, up to 1/3 for a scatter. Points on an edge between two
  /// faces, and flying pixels off the edge, have large values. 1 without a normal.
  std::vector<double> surface_variation;
};

/// Like estimateNormals, but each normal is oriented towards `viewpoint`
/// and comes with its surface variation.
ViewNormals estimateViewNormals(const std::vector<Eigen::Vector3d>& points, double radius_m,
                                const Eigen::Vector3d& viewpoint);

/// Normals of a closed convex surface sampled without them (a cuboid model
/// from a file): estimated, then turned away from the centroid of the points.
std::vector<Eigen::Vector3d> estimateOutwardNormals(const std::vector<Eigen::Vector3d>& points, double radius_m);
}  // namespace registration
}  // namespace brick_pose
