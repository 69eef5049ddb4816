#include <gtest/gtest.h>

#include "brick_pose/frame/stamp_order.h"

namespace brick_pose
{
TEST(StampOrder, DropsLateAndDuplicateFramesButFollowsARestartedBag)
{
  StampOrder order(1.0);
  const std::int64_t second = 1000000000;
  EXPECT_EQ(order.admit(100 * second), StampOrder::Verdict::kInOrder);
  EXPECT_EQ(order.admit(100 * second + 33000000), StampOrder::Verdict::kInOrder);
  EXPECT_EQ(order.admit(100 * second + 33000000), StampOrder::Verdict::kOutOfOrder) << "duplicate";
  EXPECT_EQ(order.admit(100 * second), StampOrder::Verdict::kOutOfOrder) << "late";
  EXPECT_EQ(order.lastStampNs(), 100 * second + 33000000);
  EXPECT_EQ(order.admit(40 * second), StampOrder::Verdict::kRestarted) << "bag looped";
  EXPECT_EQ(order.admit(40 * second + 33000000), StampOrder::Verdict::kInOrder);
}
}  // namespace brick_pose
