#include "brick_pose/sim/fast_random.h"

#include <array>
#include <cmath>

namespace brick_pose
{
namespace sim
{
namespace
{
std::uint64_t splitMix64(std::uint64_t& x)
{
  std::uint64_t z = (x += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

// Inverse-CDF table of the standard normal, sampled at 4096 equal-probability
// points: a lookup instead of log/cos per draw. Interpolating between two
// neighbours removes the staircase.
constexpr int kTableSize = 4096;

double inverseNormalCdf(double p)
{
  // Bisection on erfc: the table is built once, so simplicity beats speed.
  double low = -9.0, high = 9.0;
  for (int i = 0; i < 100; ++i)
  {
    const double mid = 0.5 * (low + high);
    const double cdf = 0.5 * std::erfc(-mid / std::sqrt(2.0));
    (cdf < p ? low : high) = mid;
  }
  return 0.5 * (low + high);
}

const std::array<double, kTableSize + 1>& normalTable()
{
  static const std::array<double, kTableSize + 1> table = [] {
    std::array<double, kTableSize + 1> values{};
    for (int i = 0; i <= kTableSize; ++i)
      values[i] = inverseNormalCdf((i + 0.5) / (kTableSize + 1.0));
    return values;
  }();
  return table;
}
}  // namespace

FastRandom::FastRandom(std::uint64_t seed)
{
  for (std::uint64_t& word : state_)
    word = splitMix64(seed);
}

std::uint64_t FastRandom::next()
{
  // xoshiro256+ (Blackman & Vigna): fast and statistically fine for noise.
  const std::uint64_t result = state_[0] + state_[3];
  const std::uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotl(state_[3], 45);
  return result;
}

double FastRandom::normal()
{
  const auto& table = normalTable();
  const double position = uniform() * kTableSize;
  const int index = static_cast<int>(position);
  const double fraction = position - index;
  return table[index] + fraction * (table[index + 1] - table[index]);
}
}  // namespace sim
}  // namespace brick_pose
