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

TEST(StampOrder, AShortLoopedBagRestartsOnEveryPass)
{
  // A 0.1 s bag looped: each pass jumps back far less than the 1 s gap.
  StampOrder order(1.0);
  const std::int64_t start = 5000000000, period = 33000000;
  for (int pass = 0; pass < 3; ++pass)
    for (int frame = 0; frame < 4; ++frame)
    {
      const StampOrder::Verdict expected = frame > 0   ? StampOrder::Verdict::kInOrder
                                           : pass == 0 ? StampOrder::Verdict::kInOrder
                                                       : StampOrder::Verdict::kRestarted;
      EXPECT_EQ(order.admit(start + frame * period), expected) << "pass " << pass << " frame " << frame;
    }
}

TEST(StampOrder, ALateFrameInsideTheSequenceIsStillDropped)
{
  StampOrder order(1.0);
  const std::int64_t start = 5000000000, period = 33000000;
  for (int frame = 0; frame < 5; ++frame) EXPECT_EQ(order.admit(start + frame * period), StampOrder::Verdict::kInOrder);
  EXPECT_EQ(order.admit(start + 2 * period), StampOrder::Verdict::kOutOfOrder);
  EXPECT_EQ(order.admit(start + 4 * period), StampOrder::Verdict::kOutOfOrder) << "duplicate";
}

TEST(StampOrder, TheClockGoingBackRestartsWhateverTheStamps)
{
  StampOrder order(1.0);
  EXPECT_EQ(order.admit(2000000000), StampOrder::Verdict::kInOrder);
  EXPECT_EQ(order.admit(2100000000), StampOrder::Verdict::kInOrder);
  EXPECT_EQ(order.admit(2050000000, /*clock_went_back=*/true), StampOrder::Verdict::kRestarted);
}
}  // namespace brick_pose
