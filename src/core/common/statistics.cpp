#include "brick_pose/common/statistics.h"

#include <algorithm>
#include <cmath>
#include <ctime>

namespace brick_pose
{
double percentile(std::vector<double> values, double fraction)
{
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  const double position = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(values.size() - 1, below + 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

double upperMedianInPlace(std::vector<double>& values)
{
  if (values.empty()) return std::nan("");
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

RobustSpread robustSpread(std::vector<double> values)
{
  RobustSpread spread;
  spread.centre = upperMedianInPlace(values);
  if (values.empty()) return spread;
  for (double& value : values) value = std::abs(value - spread.centre);
  spread.sigma = 1.4826 * upperMedianInPlace(values);
  return spread;
}

double mean(const std::vector<double>& values)
{
  if (values.empty()) return std::nan("");
  double sum = 0.0;
  for (const double value : values) sum += value;
  return sum / static_cast<double>(values.size());
}

double threadCpuSeconds()
{
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}
}  // namespace brick_pose
