#include "brick_pose/sim/scene.h"

#include <cmath>

namespace brick_pose
{
namespace sim
{
std::array<Eigen::Vector3d, 4> topFaceCornersInCamera(const BrickTruth& truth)
{
  BrickType type;
  type.length_m = truth.dimensions_m.x();
  type.width_m = truth.dimensions_m.y();
  std::array<Eigen::Vector3d, 4> corners = topFaceCornersInBrick(type);
  for (Eigen::Vector3d& corner : corners)
    corner = truth.camera_T_brick * corner;
  return corners;
}

Eigen::Isometry3d brickTFace(const BrickType& type, CuboidFace face)
{
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  const double half_h = 0.5 * type.height_m;
  Eigen::Vector3d normal, along;
  switch (face)
  {
    case CuboidFace::kPlusX:
    case CuboidFace::kMinusX:
      normal = (face == CuboidFace::kPlusX ? 1.0 : -1.0) * Eigen::Vector3d::UnitX();
      frame.translation() = 0.5 * type.length_m * normal - half_h * Eigen::Vector3d::UnitZ();
      along = type.width_m >= type.height_m ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
      break;
    case CuboidFace::kPlusY:
    case CuboidFace::kMinusY:
      normal = (face == CuboidFace::kPlusY ? 1.0 : -1.0) * Eigen::Vector3d::UnitY();
      frame.translation() = 0.5 * type.width_m * normal - half_h * Eigen::Vector3d::UnitZ();
      along = type.length_m >= type.height_m ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitZ();
      break;
    case CuboidFace::kBottom:
      frame.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
      frame.translation() = -type.height_m * Eigen::Vector3d::UnitZ();
      return frame;
    default:
      return frame;
  }
  frame.linear().col(0) = along;
  frame.linear().col(1) = normal.cross(along);
  frame.linear().col(2) = normal;
  return frame;
}

Resting restingWithFaceUp(CuboidFace face)
{
  switch (face)
  {
    case CuboidFace::kPlusX:
    case CuboidFace::kMinusX: return Resting::kOnEnd;
    case CuboidFace::kPlusY:
    case CuboidFace::kMinusY: return Resting::kOnSide;
    default: return Resting::kUpright;
  }
}
}  // namespace sim
}  // namespace brick_pose
