#pragma once
// Keeps frames in time order. A frame not after the previous one (a late or
// duplicated message) is dropped. A jump back is a restarted or looped bag
// instead, which starts a new sequence, when
//  - the clock itself went back (rosbag play --clock restarts /clock), or
//  - the stamp is back at (or before) the start of a sequence of at least
//    three frames (a loop replays the bag's first frame), or
//  - it jumps back further than `restart_gap_s`.
// A bag of any length, looped, is then processed on every pass.

#include <cstdint>

namespace brick_pose
{
class StampOrder
{
public:
  enum class Verdict
  {
    kInOrder,
    kRestarted,   ///< back in time: accepted, the sequence starts over
    kOutOfOrder,  ///< not after the previous frame: drop it
  };

  explicit StampOrder(double restart_gap_s = 1.0) : restart_gap_ns_(static_cast<std::int64_t>(restart_gap_s * 1e9)) {}

  /// Judges `stamp_ns` against the last accepted stamp and remembers it when
  /// accepted. `clock_went_back`: the receiver's clock jumped back since the
  /// previous call.
  Verdict admit(std::int64_t stamp_ns, bool clock_went_back = false);

  std::int64_t lastStampNs() const { return last_ns_; }

private:
  static constexpr int kMinFramesForLoop = 3;
  std::int64_t restart_gap_ns_;
  std::int64_t first_ns_ = 0;
  std::int64_t last_ns_ = 0;
  int frames_in_sequence_ = 0;
  bool started_ = false;
};
}  // namespace brick_pose
