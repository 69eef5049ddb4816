#pragma once
// Parameters and reports speak degrees; the maths works in radians. One
// definition of pi and of the two conversions for the whole code base.

namespace brick_pose
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;
constexpr double kRadToDeg = 180.0 / kPi;
}  // namespace brick_pose
