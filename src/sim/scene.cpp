#include "brick_pose/sim/scene.h"

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
}  // namespace sim
}  // namespace brick_pose
