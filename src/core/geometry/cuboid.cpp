#include "brick_pose/geometry/cuboid.h"

namespace brick_pose
{
std::array<Eigen::Vector3d, 4> topFaceCornersInBrick(const BrickType& type)
{
  const double x = 0.5 * type.length_m, y = 0.5 * type.width_m;
  return {{Eigen::Vector3d(x, y, 0.0), Eigen::Vector3d(-x, y, 0.0), Eigen::Vector3d(-x, -y, 0.0),
           Eigen::Vector3d(x, -y, 0.0)}};
}

std::array<Eigen::Vector3d, 8> cuboidCornersInBrick(const BrickType& type)
{
  std::array<Eigen::Vector3d, 8> corners;
  const std::array<Eigen::Vector3d, 4> top = topFaceCornersInBrick(type);
  for (int i = 0; i < 4; ++i)
  {
    corners[i] = top[i];
    corners[i + 4] = top[i] - Eigen::Vector3d(0.0, 0.0, type.height_m);
  }
  return corners;
}
}  // namespace brick_pose
