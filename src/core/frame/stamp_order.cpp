#include "brick_pose/frame/stamp_order.h"

namespace brick_pose
{
StampOrder::Verdict StampOrder::admit(std::int64_t stamp_ns, bool clock_went_back)
{
  Verdict verdict = Verdict::kInOrder;
  if (started_ && stamp_ns <= last_ns_)
  {
    // "Back at the start" needs a sequence of a few frames: right after its
    // first frame, a late frame and a replay look the same.
    const bool back_at_start = frames_in_sequence_ >= kMinFramesForLoop && stamp_ns <= first_ns_;
    const bool restart = clock_went_back || back_at_start || last_ns_ - stamp_ns > restart_gap_ns_;
    if (!restart) return Verdict::kOutOfOrder;
    verdict = Verdict::kRestarted;
  }
  if (!started_ || verdict == Verdict::kRestarted)
  {
    first_ns_ = stamp_ns;
    frames_in_sequence_ = 0;
  }
  ++frames_in_sequence_;
  started_ = true;
  last_ns_ = stamp_ns;
  return verdict;
}
}  // namespace brick_pose
