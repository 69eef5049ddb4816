#pragma once
// Numbers in messages: short enough to read, as many digits as the message needs.

#include <string>

namespace brick_pose
{
/// `value` with at most `significant_digits` digits (stream default notation),
/// e.g. 0.8312 at 3 digits reads "0.831".
std::string numberText(double value, int significant_digits);
}  // namespace brick_pose
