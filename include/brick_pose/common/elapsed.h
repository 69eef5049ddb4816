#pragma once
// Wall time spent since a start: stage timings and time budgets.

#include <chrono>

namespace brick_pose
{
using SteadyClock = std::chrono::steady_clock;

inline double secondsSince(SteadyClock::time_point start)
{
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

inline double millisecondsSince(SteadyClock::time_point start) { return 1e3 * secondsSince(start); }
}  // namespace brick_pose
