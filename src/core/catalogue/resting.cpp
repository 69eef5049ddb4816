#include "brick_pose/catalogue/resting.h"

#include <algorithm>

namespace brick_pose
{
const char* toString(Resting resting)
{
  switch (resting)
  {
    case Resting::kUpright: return "upright";
    case Resting::kOnSide: return "on_side";
    case Resting::kOnEnd: return "on_end";
  }
  return "upright";
}

BrickType restingAs(const BrickType& type, Resting resting)
{
  if (resting == Resting::kUpright) return type;
  const bool on_side = resting == Resting::kOnSide;
  BrickType variant = type;
  variant.name = type.name + (on_side ? " lying on a side" : " standing on an end");
  const double up_a_m = on_side ? type.length_m : type.width_m;
  variant.length_m = std::max(up_a_m, type.height_m);
  variant.width_m = std::min(up_a_m, type.height_m);
  variant.height_m = on_side ? type.width_m : type.length_m;
  variant.resting = resting;
  variant.catalogue_name = type.name;
  return variant;
}
}  // namespace brick_pose
