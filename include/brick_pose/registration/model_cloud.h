#pragma once
// Artificial model clouds of a brick in the brick frame (see
// brick_catalogue.h): origin at the centre of the top face, x along the long
// edge, y along the short edge, z out of the top face.

#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/registration/point_set.h"

namespace brick_pose
{
namespace registration
{
/// The side faces, named by their outward normal in the brick frame.
enum class BrickSide
{
  kPlusX,
  kMinusX,
  kPlusY,
  kMinusY
};

struct ModelCloudParams
{
  double spacing_m = 0.01;  ///< grid step on every face
  std::vector<BrickSide> sides;  ///< side faces to add to the top face
};

/// Top face (z = 0, normals +z) plus the requested side faces (normals
/// outward), each sampled on a grid that includes the face's edges. Throws
/// ConfigError for an invalid brick type or spacing.
PointSet buildBrickModelCloud(const BrickType& brick, const ModelCloudParams& options = ModelCloudParams());

/// The whole surface of the cuboid: all six faces (top, bottom and the four
/// sides), each on a grid of spacing_m that includes its edges, with outward
/// normals; a point on an edge belongs to one face only, so every spot of the
/// surface is sampled about equally densely. The model of whole-cuboid views
/// (a camera sees one to three faces, which ones depends on the pose), where
/// the visible part is chosen per pose by the view check (view_consistency.h).
/// Throws ConfigError for an invalid brick type or spacing.
PointSet buildCuboidSurfaceCloud(const BrickType& brick, double spacing_m = 0.01);

/// The side faces a camera sees for a brick pose (faces whose outward normal
/// points towards the camera centre). camera_from_brick maps brick points into
/// the camera frame.
std::vector<BrickSide> visibleSides(const BrickType& brick, const Eigen::Isometry3d& camera_from_brick);
}  // namespace registration
}  // namespace brick_pose
