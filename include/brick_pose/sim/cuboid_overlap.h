#pragma once
// Whether two placed bricks interpenetrate, and moving a brick clear of
// others. Piles used to hold bricks inside each other, which no real pile
// does: the unorganised pile rests each brick on a grid of support samples,
// and a neighbour's corner between two samples ended up inside it; in an
// organised pile a long brick turned by its 2 deg of jitter reached into the
// next row. A neighbour's side face then crossed a top at the top's own
// depth.

#include <vector>

#include "brick_pose/sim/scene.h"

namespace brick_pose
{
namespace sim
{
/// How deep `a` and `b` interpenetrate, metres: the smallest overlap of
/// their projections on the separating-axis candidates of two boxes (the 6
/// face normals and 9 edge cross products). <= 0 when they are apart.
double interpenetrationM(const PlacedBrick& a, const PlacedBrick& b);

/// Moves `brick` along the unit `direction` until it interpenetrates none of
/// `placed` by more than `tolerance_m` (a negative tolerance: until that far
/// apart).
void moveClearOf(PlacedBrick& brick, const std::vector<PlacedBrick>& placed, const Eigen::Vector3d& direction,
                 double tolerance_m = 0.0005);

/// moveClearOf() upwards: a dropped brick comes to rest on what it met.
inline void liftClearOf(PlacedBrick& brick, const std::vector<PlacedBrick>& placed, double tolerance_m = 0.0005)
{
  moveClearOf(brick, placed, Eigen::Vector3d::UnitZ(), tolerance_m);
}
}  // namespace sim
}  // namespace brick_pose
