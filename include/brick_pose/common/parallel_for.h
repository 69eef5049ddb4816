#pragma once

#include <functional>

namespace brick_pose
{
/// Runs task(i) for every i in [0, count) on up to worker_count threads, the
/// calling thread being one of them, and returns when all are done.
///
/// Workers take the next index from a shared counter, so one long task (the
/// big face of a long brick) does not hold back the short ones queued behind
/// it. Tasks must not share mutable state except through their index. The
/// first exception a task throws is rethrown here once every worker stopped;
/// the remaining indices are then skipped.
void parallelFor(int count, int worker_count, const std::function<void(int)>& task);
}  // namespace brick_pose
