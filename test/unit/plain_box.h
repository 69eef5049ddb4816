#pragma once
// A catalogue type for tests: a plain box (no plate colour) of a size.

#include <string>

#include "brick_pose/catalogue/brick_catalogue.h"

namespace brick_pose
{
inline BrickType plainBox(const std::string& name, double length_m, double width_m, double height_m)
{
  BrickType type;
  type.name = name;
  type.length_m = length_m;
  type.width_m = width_m;
  type.height_m = height_m;
  return type;
}
}  // namespace brick_pose
