#pragma once
// Layouts of the scene kinds that model real piles: touching rows, pallet
// layers and stacks, and boxes on a table. Used by SceneGenerator; each
// draws everything it needs from the one seeded random source, so a seed
// gives the same scene on every platform.

#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/sim/fast_random.h"
#include "brick_pose/sim/scene.h"
#include "brick_pose/sim/scene_generator.h"

namespace brick_pose
{
namespace sim
{
struct LayoutContext
{
  std::vector<const BrickType*> types;  ///< the types to draw from, never empty
  const SceneParams& params;
  FastRandom& random;
};

std::vector<PlacedBrick> touchingRows(LayoutContext& context);
std::vector<PlacedBrick> palletLayer(LayoutContext& context);
std::vector<PlacedBrick> palletStack(LayoutContext& context);
std::vector<PlacedBrick> tableBoxes(LayoutContext& context);

/// Height of the highest surface under `brick`'s lowest face among `placed`
/// (0 = the ground). Works for bricks lying flat or standing on a side.
double supportHeightUnder(const PlacedBrick& brick, const std::vector<PlacedBrick>& placed);

/// Moves `brick` vertically so that its lowest corner is at `floor_z`.
void restBrickOn(PlacedBrick& brick, double floor_z);
}  // namespace sim
}  // namespace brick_pose
