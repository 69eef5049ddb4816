#include "brick_pose/frame/stamp_order.h"

namespace brick_pose
{
StampOrder::Verdict StampOrder::admit(std::int64_t stamp_ns)
{
  Verdict verdict = Verdict::kInOrder;
  if (started_ && stamp_ns <= last_ns_)
  {
    if (last_ns_ - stamp_ns <= restart_gap_ns_) return Verdict::kOutOfOrder;
    verdict = Verdict::kRestarted;
  }
  started_ = true;
  last_ns_ = stamp_ns;
  return verdict;
}
}  // namespace brick_pose
