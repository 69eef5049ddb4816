#include "brick_pose/segmentation/depth_noise.h"

#include <algorithm>
#include <cmath>

#include "brick_pose/common/statistics.h"

namespace brick_pose
{
double estimateNoiseAt1m(std::vector<double> normalised_mse, double quantile, double min_at_1m_m,
                         double max_at_1m_m, double fallback_at_1m_m)
{
  if (normalised_mse.empty()) return fallback_at_1m_m;
  const double at_1m_m = std::sqrt(std::max(0.0, percentile(std::move(normalised_mse), quantile)));
  return std::clamp(at_1m_m, min_at_1m_m, max_at_1m_m);
}
}  // namespace brick_pose
