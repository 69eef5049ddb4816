#pragma once
// Keeps frames in time order. A frame older than the previous one (a late or
// duplicated message) is dropped; a jump back by more than `restart_gap_s`
// is a restarted or looped bag, which starts a new sequence instead of
// blocking every frame that follows.

#include <cstdint>

namespace brick_pose
{
class StampOrder
{
public:
  enum class Verdict
  {
    kInOrder,
    kRestarted,   ///< far back in time: accepted, the sequence starts over
    kOutOfOrder,  ///< not after the previous frame: drop it
  };

  explicit StampOrder(double restart_gap_s = 1.0) : restart_gap_ns_(static_cast<std::int64_t>(restart_gap_s * 1e9)) {}

  /// Judges `stamp_ns` against the last accepted stamp and remembers it when accepted.
  Verdict admit(std::int64_t stamp_ns);

  std::int64_t lastStampNs() const { return last_ns_; }

private:
  std::int64_t restart_gap_ns_;
  std::int64_t last_ns_ = 0;
  bool started_ = false;
};
}  // namespace brick_pose
