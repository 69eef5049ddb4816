#pragma once
// The order in which the registration stage takes a frame's candidates when
// its per-frame budget cannot cover them all. Candidates are matched to the
// bricks of earlier frames (same type, centre within a few centimetres);
// the one registered longest ago goes first, and one never registered before
// all. A static scene with more bricks than one frame's budget then has
// every brick registered within a few frames, instead of the same ones
// skipped forever.

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/roi/brick_candidate.h"

namespace brick_pose
{
struct RegistrationOrderParams
{
  /// Candidates of two frames are the same brick when their types agree and
  /// their face centres are closer than this.
  double match_radius_m = 0.05;
  /// A remembered brick not seen for this many frames is forgotten.
  int forget_after_frames = 30;

  void validate() const;  ///< Throws ConfigError naming the field.
};

class RegistrationOrder
{
public:
  explicit RegistrationOrder(const RegistrationOrderParams& params = RegistrationOrderParams());

  /// Indices into `candidates`, most overdue first (ties keep the front
  /// end's order). Starts a new frame.
  std::vector<std::size_t> order(const std::vector<BrickCandidate>& candidates);

  /// Records that `candidate`, of the frame last ordered, was registered (or
  /// attempted: one Super4PCS cannot register is not retried first either).
  void attempted(const BrickCandidate& candidate);

  /// Bricks remembered from recent frames.
  std::size_t rememberedBricks() const { return memory_.size(); }

private:
  struct Remembered
  {
    std::string type_name;
    Eigen::Vector3d centre_m;
    std::int64_t last_attempt_frame = -1;  ///< -1: seen, never attempted
    std::int64_t last_seen_frame = 0;
  };
  Remembered* find(const BrickCandidate& candidate);

  RegistrationOrderParams params_;
  std::vector<Remembered> memory_;
  std::int64_t frame_ = 0;
};
}  // namespace brick_pose
