// The shared summary statistics: the interpolated percentile the README's
// figures use, and the upper median and robust spread the seam and edge
// tests use.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "brick_pose/common/statistics.h"

namespace brick_pose
{
TEST(Statistics, PercentileInterpolatesAnEvenCount)
{
  EXPECT_DOUBLE_EQ(percentile({4.0, 1.0, 3.0, 2.0}, 0.5), 2.5);
  EXPECT_TRUE(std::isnan(percentile({}, 0.5)));
}

TEST(Statistics, UpperMedianTakesTheHigherMiddleValue)
{
  std::vector<double> odd{5.0, 1.0, 3.0};
  EXPECT_DOUBLE_EQ(upperMedianInPlace(odd), 3.0);
  std::vector<double> even{4.0, 1.0, 3.0, 2.0};
  EXPECT_DOUBLE_EQ(upperMedianInPlace(even), 3.0);
  std::vector<double> none;
  EXPECT_TRUE(std::isnan(upperMedianInPlace(none)));
}

TEST(Statistics, RobustSpreadIgnoresAnOutlier)
{
  // Deviations from the median 3: {2, 1, 0, 1, 97}; their upper median is 1.
  const RobustSpread spread = robustSpread({1.0, 2.0, 3.0, 4.0, 100.0});
  EXPECT_DOUBLE_EQ(spread.centre, 3.0);
  EXPECT_DOUBLE_EQ(spread.sigma, 1.4826);
  const RobustSpread empty = robustSpread({});
  EXPECT_TRUE(std::isnan(empty.centre));
  EXPECT_DOUBLE_EQ(empty.sigma, 0.0);
}
}  // namespace brick_pose
