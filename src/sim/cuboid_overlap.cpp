#include "brick_pose/sim/cuboid_overlap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace brick_pose
{
namespace sim
{
namespace
{
/// A brick as a box: its centre (the brick's origin is its top-face
/// centre), axes and half extents.
struct Box
{
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;
  Eigen::Vector3d half_m;
};

Box boxOf(const PlacedBrick& brick)
{
  const BrickType& type = brick.type;
  return {brick.world_T_brick * Eigen::Vector3d(0.0, 0.0, -0.5 * type.height_m), brick.world_T_brick.linear(),
          0.5 * Eigen::Vector3d(type.length_m, type.width_m, type.height_m)};
}

double radiusAlong(const Box& box, const Eigen::Vector3d& axis)
{
  double radius = 0.0;
  for (int k = 0; k < 3; ++k) radius += box.half_m[k] * std::abs(box.axes.col(k).dot(axis));
  return radius;
}

/// Overlap of the two boxes' projections on the unit `axis`.
double overlapAlong(const Box& a, const Box& b, const Eigen::Vector3d& axis)
{
  return radiusAlong(a, axis) + radiusAlong(b, axis) - std::abs((b.centre - a.centre).dot(axis));
}
}  // namespace

double interpenetrationM(const PlacedBrick& a, const PlacedBrick& b)
{
  const Box box_a = boxOf(a), box_b = boxOf(b);
  double smallest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
  {
    smallest = std::min(smallest, overlapAlong(box_a, box_b, box_a.axes.col(i)));
    smallest = std::min(smallest, overlapAlong(box_a, box_b, box_b.axes.col(i)));
    for (int j = 0; j < 3; ++j)
    {
      const Eigen::Vector3d cross = box_a.axes.col(i).cross(box_b.axes.col(j));
      // Parallel edges give no axis of their own (the face normals cover them).
      if (cross.norm() > 1e-9) smallest = std::min(smallest, overlapAlong(box_a, box_b, cross.normalized()));
    }
  }
  return smallest;
}

void moveClearOf(PlacedBrick& brick, const std::vector<PlacedBrick>& placed, const Eigen::Vector3d& direction,
                 double tolerance_m)
{
  // Each step moves by the deepest overlap: along an axis other than
  // `direction` that frees less than it moves, so a few steps may be
  // needed; the cap only guards against a degenerate pose.
  constexpr int kMaxSteps = 200;
  constexpr double kMinStepM = 0.001;
  for (int step = 0; step < kMaxSteps; ++step)
  {
    double deepest_m = -std::numeric_limits<double>::infinity();
    for (const PlacedBrick& other : placed) deepest_m = std::max(deepest_m, interpenetrationM(brick, other));
    if (deepest_m <= tolerance_m) return;
    brick.world_T_brick.translation() += std::max(deepest_m - tolerance_m, kMinStepM) * direction;
  }
}
}  // namespace sim
}  // namespace brick_pose
