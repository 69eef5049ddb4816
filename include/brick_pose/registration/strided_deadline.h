#pragma once
// The time budget of a 4-point search, checked inside its candidate loop.

#include "brick_pose/registration/icp_polish.h"

namespace brick_pose
{
namespace registration
{
/// Says whether `max_time_s` since `start` has passed, but reads the clock
/// only on every `stride`-th call: candidates are cheap, a clock read per
/// candidate would cost as much as the candidates themselves.
class StridedDeadline
{
public:
  StridedDeadline(SteadyClock::time_point start, double max_time_s, int stride)
    : start_(start), max_time_s_(max_time_s), stride_(stride)
  {
  }

  bool passed()
  {
    if (++calls_since_clock_ < stride_) return false;
    calls_since_clock_ = 0;
    return secondsSince(start_) >= max_time_s_;
  }

private:
  SteadyClock::time_point start_;
  double max_time_s_;
  int stride_;
  int calls_since_clock_ = 0;
};
}  // namespace registration
}  // namespace brick_pose
