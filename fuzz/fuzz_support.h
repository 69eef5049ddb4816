#pragma once
// Helpers shared by the libFuzzer targets: decoding doubles that include the
// values a broken sensor or driver produces (NaN, +-Inf, 0, denormals, huge),
// which FuzzedDataProvider::ConsumeFloatingPoint never returns on its own.
//
// Policy of every target: the core documents InputError / ConfigError as the
// way it refuses input, and the nodelets catch only those. Any other exception
// escaping an entry point would take down the nodelet manager, so the targets
// let it escape and libFuzzer reports it as a crash.

#include <cstdint>
#include <limits>

#include <fuzzer/FuzzedDataProvider.h>

namespace brick_pose
{
namespace fuzz
{
/// Mostly a value in [low, high]; one time in eight a special value.
inline double consumeDouble(FuzzedDataProvider& input, double low, double high)
{
  if (input.ConsumeIntegralInRange<int>(0, 7) != 0) return input.ConsumeFloatingPointInRange<double>(low, high);
  switch (input.ConsumeIntegralInRange<int>(0, 6))
  {
    case 0: return std::numeric_limits<double>::quiet_NaN();
    case 1: return std::numeric_limits<double>::infinity();
    case 2: return -std::numeric_limits<double>::infinity();
    case 3: return 0.0;
    case 4: return std::numeric_limits<double>::denorm_min();
    case 5: return std::numeric_limits<double>::max();
    default: return input.ConsumeFloatingPoint<double>();  // anything finite
  }
}

/// Calls `trap` when `condition` does not hold: an invariant the header
/// promises was broken (reported by libFuzzer as a crash with a stack).
inline void require(bool condition)
{
  if (!condition) __builtin_trap();
}
}  // namespace fuzz
}  // namespace brick_pose
