#pragma once
// What a benchmark needs to know about where and how it runs: the source
// tree (data in, results out), the clocks and the machine's load, which
// every timing figure is quoted with.

#include <chrono>
#include <string>

#include "brick_pose/common/elapsed.h"

namespace brick_pose
{
namespace bench
{
/// The source tree: BRICK_POSE_SOURCE_DIR from the build, else the
/// environment variable of that name, else the working directory.
std::string sourceDirectory();

/// bench/results under the source tree.
std::string defaultOutputDir();

/// Creates `path` and its parents; true when it exists as a directory afterwards.
bool makeDirectories(const std::string& path);

/// 1-minute load average, -1 when unknown.
double loadAverage();

/// CPU time of the whole process (all threads) in milliseconds: unlike the
/// wall time it does not grow while other processes hold the cores.
double processCpuMs();
}  // namespace bench
}  // namespace brick_pose
