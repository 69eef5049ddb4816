// parallelFor: every index once, on any number of workers, and a task's
// exception reaches the caller.
#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "brick_pose/common/parallel_for.h"

namespace brick_pose
{
namespace
{
TEST(ParallelFor, RunsEveryIndexExactlyOnce)
{
  for (int workers : {1, 2, 3, 8})
    for (int count : {0, 1, 2, 7, 100})
    {
      std::vector<std::atomic<int>> runs(count);
      parallelFor(count, workers, [&](int i) { ++runs[i]; });
      for (int i = 0; i < count; ++i) EXPECT_EQ(runs[i].load(), 1) << "index " << i << ", " << workers << " workers";
    }
}

TEST(ParallelFor, NonPositiveWorkerCountRunsInTheCaller)
{
  int sum = 0;  // unsynchronised on purpose: one thread only
  parallelFor(10, 0, [&](int i) { sum += i; });
  EXPECT_EQ(sum, 45);
}

TEST(ParallelFor, TaskExceptionReachesTheCaller)
{
  std::atomic<int> runs{0};
  EXPECT_THROW(parallelFor(50, 2,
                           [&](int i) {
                             ++runs;
                             if (i == 3) throw std::runtime_error("task 3 failed");
                           }),
               std::runtime_error);
  EXPECT_GE(runs.load(), 4);
}
}  // namespace
}  // namespace brick_pose
