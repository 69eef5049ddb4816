#pragma once
// Summary statistics and clocks shared by the benchmarks, the latency tool
// and the stage timing. One definition of a percentile for every figure the
// README quotes: linear interpolation between the closest ranks (NumPy's
// default, "type 7"), so p50 of an even count is the mean of the middle two.

#include <vector>

namespace brick_pose
{
/// The `fraction` (0..1) percentile of `values`, interpolated linearly
/// between closest ranks; NaN when `values` is empty.
double percentile(std::vector<double> values, double fraction);

/// Arithmetic mean; NaN when `values` is empty.
double mean(const std::vector<double>& values);

/// CPU time of the calling thread in seconds. Unlike wall time it does not
/// grow when other processes share the cores.
double threadCpuSeconds();
}  // namespace brick_pose
