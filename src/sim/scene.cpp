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
  if (face == CuboidFace::kBottom)
  {
    frame.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
    frame.translation() = -type.height_m * Eigen::Vector3d::UnitZ();
    return frame;
  }
  const Resting resting = restingWithFaceUp(face);
  if (resting == Resting::kUpright) return frame;
  // An end (±x) spans the width and the height, a side (±y) the length and
  // the height; the box reaches half its length or width out to it.
  const bool end = resting == Resting::kOnEnd;
  const bool plus = face == CuboidFace::kPlusX || face == CuboidFace::kPlusY;
  const Eigen::Vector3d normal = (plus ? 1.0 : -1.0) * (end ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
  const Eigen::Vector3d across = end ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
  const double across_m = end ? type.width_m : type.length_m;
  const double out_m = end ? type.length_m : type.width_m;
  frame.translation() = 0.5 * out_m * normal - half_h * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d along = across_m >= type.height_m ? across : Eigen::Vector3d::UnitZ();
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
