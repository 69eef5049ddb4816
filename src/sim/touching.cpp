#include "brick_pose/sim/touching.h"

#include <algorithm>
#include <cmath>

namespace brick_pose
{
namespace sim
{
namespace
{
// Samples keep this far from a side face's own edges, so that bricks meeting
// only at a corner or a stacked brick resting on the top edge do not count.
constexpr double kEdgeMarginM = 0.005;
constexpr int kSamplesAlong = 8;
constexpr int kSamplesDown = 4;

bool inside(const PlacedBrick& brick, const Eigen::Isometry3d& brick_T_world, const Eigen::Vector3d& point_world)
{
  const Eigen::Vector3d local = brick_T_world * point_world;
  return std::abs(local.x()) <= 0.5 * brick.type.length_m && std::abs(local.y()) <= 0.5 * brick.type.width_m &&
         local.z() <= 0.0 && local.z() >= -brick.type.height_m;
}

/// Points `tolerance_m` outside each side face of `brick`, on a grid over the
/// face. Side faces are the four whose normals are nearest horizontal in the
/// world: for a box standing on an end, its catalogue top is one of them.
std::vector<Eigen::Vector3d> sideProbes(const PlacedBrick& brick, double tolerance_m)
{
  const Eigen::Vector3d low(-0.5 * brick.type.length_m, -0.5 * brick.type.width_m, -brick.type.height_m);
  const Eigen::Vector3d high(0.5 * brick.type.length_m, 0.5 * brick.type.width_m, 0.0);
  int vertical = 2;
  for (int axis = 0; axis < 3; ++axis)
    if (std::abs(brick.world_T_brick.linear()(2, axis)) > std::abs(brick.world_T_brick.linear()(2, vertical)))
      vertical = axis;
  const auto spread = [&](int axis, int index, int count) {
    const double margin = std::min(kEdgeMarginM, 0.25 * (high[axis] - low[axis]));
    return low[axis] + margin + (high[axis] - low[axis] - 2.0 * margin) * (index + 0.5) / count;
  };
  std::vector<Eigen::Vector3d> probes;
  for (int axis = 0; axis < 3; ++axis)
  {
    if (axis == vertical) continue;
    const int along = 3 - axis - vertical;
    for (const bool positive : {false, true})
      for (int i = 0; i < kSamplesAlong; ++i)
        for (int j = 0; j < kSamplesDown; ++j)
        {
          Eigen::Vector3d local;
          local[axis] = positive ? high[axis] + tolerance_m : low[axis] - tolerance_m;
          local[along] = spread(along, i, kSamplesAlong);
          local[vertical] = spread(vertical, j, kSamplesDown);
          probes.push_back(brick.world_T_brick * local);
        }
  }
  return probes;
}
}  // namespace

std::vector<int> touchingNeighbourCounts(const Scene& scene, double tolerance_m)
{
  const int count = static_cast<int>(scene.bricks.size());
  std::vector<Eigen::Isometry3d> brick_T_world;
  for (const PlacedBrick& brick : scene.bricks)
    brick_T_world.push_back(brick.world_T_brick.inverse());
  // Symmetric: a small brick against a long one may miss the long one's
  // probes but not the other way round.
  std::vector<std::vector<bool>> touches(count, std::vector<bool>(count, false));
  for (int a = 0; a < count; ++a)
  {
    const std::vector<Eigen::Vector3d> probes = sideProbes(scene.bricks[a], tolerance_m);
    for (int b = 0; b < count; ++b)
    {
      if (b == a) continue;
      for (const Eigen::Vector3d& probe : probes)
        if (inside(scene.bricks[b], brick_T_world[b], probe))
        {
          touches[a][b] = touches[b][a] = true;
          break;
        }
    }
  }
  std::vector<int> neighbours(count, 0);
  for (int a = 0; a < count; ++a)
    for (int b = 0; b < count; ++b)
      neighbours[a] += touches[a][b] ? 1 : 0;
  return neighbours;
}
}  // namespace sim
}  // namespace brick_pose
