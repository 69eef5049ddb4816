#include "brick_pose/common/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace brick_pose
{
void parallelFor(int count, int worker_count, const std::function<void(int)>& task)
{
  const int workers = std::clamp(worker_count, 1, std::max(1, count));
  if (workers == 1)
  {
    for (int i = 0; i < count; ++i) task(i);
    return;
  }
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto work = [&]() {
    for (int i = next++; i < count && !failed; i = next++)
    {
      try
      {
        task(i);
      }
      catch (...)
      {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> helpers;
  helpers.reserve(workers - 1);
  for (int w = 1; w < workers; ++w) helpers.emplace_back(work);
  work();
  for (std::thread& helper : helpers) helper.join();
  if (first_error) std::rethrow_exception(first_error);
}
}  // namespace brick_pose
