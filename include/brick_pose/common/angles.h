#pragma once
// Parameters and reports speak degrees; the maths works in radians.

#include <cmath>

namespace brick_pose
{
constexpr double kDegToRad = M_PI / 180.0;
}  // namespace brick_pose
