#pragma once
// Which bricks of a scene touch: side faces within a few millimetres of
// another brick, as in pallet layers and rows packed without gaps. Ground
// truth for the "touching recall" of the benchmark.

#include <vector>

#include "brick_pose/sim/scene.h"

namespace brick_pose
{
namespace sim
{
/// For each brick, the number of other bricks that come within `tolerance_m`
/// of one of its four side faces (top and bottom contacts, i.e. stacking,
/// do not count).
std::vector<int> touchingNeighbourCounts(const Scene& scene, double tolerance_m = kTouchingToleranceM);
}  // namespace sim
}  // namespace brick_pose
