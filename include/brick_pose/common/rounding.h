#pragma once
// Rounding an image coordinate to a pixel index, in the hot loops of the ROI
// stage (edge profiles, the tiling grid, side faces).
//
// std::lround is an out-of-line libm call: on a pile it was 8% of the front
// end's instructions (callgrind). roundToInt() gives exactly what
// static_cast<int>(std::lround(x)) gives, inline: halves away from zero, and
// the library's own answer for NaN and values too large for the quick path,
// so switching to it changes no result.

#include <cmath>

namespace brick_pose
{
inline int roundToInt(double value)
{
  // Beyond 2^62 (and for NaN, which fails the test) the library decides.
  constexpr double kQuickLimit = 4611686018427387904.0;
  if (!(std::abs(value) < kQuickLimit)) return static_cast<int>(std::lround(value));
  const long truncated = static_cast<long>(value);
  // Exact: |value| < 2^62, so value - trunc(value) is representable.
  const double fraction = value - static_cast<double>(truncated);
  long rounded = truncated;
  if (fraction >= 0.5) ++rounded;
  else if (fraction <= -0.5) --rounded;
  return static_cast<int>(rounded);
}
}  // namespace brick_pose
