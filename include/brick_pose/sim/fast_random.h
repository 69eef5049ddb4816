#pragma once
// A small deterministic random source for the renderer. std::normal_distribution
// costs ~20 ns a draw, which at four draws per pixel of a 1280x720 frame is
// most of a frame's budget; this one costs a few ns and gives the same
// sequence on every platform for a given seed.

#include <cstdint>

namespace brick_pose
{
namespace sim
{
class FastRandom
{
public:
  explicit FastRandom(std::uint64_t seed);

  std::uint64_t next();
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  /// Standard normal sample (mean 0, sigma 1).
  double normal();
  bool bernoulli(double probability) { return uniform() < probability; }

private:
  std::uint64_t state_[4];
};
}  // namespace sim
}  // namespace brick_pose
