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

/// The upper median: the middle value of an odd count, the higher of the
/// middle two of an even one; NaN when `values` is empty. It reorders
/// `values` partially instead of copying them (O(n)): the seam and edge
/// tests call it per image column, where `percentile`'s sort would cost
/// more than reading the pixels.
double upperMedianInPlace(std::vector<double>& values);

/// Centre and robust spread of a sample: its upper median and 1.4826 x the
/// upper median of the absolute deviations from it (the standard deviation
/// for normal noise, unmoved by a few outliers such as a seam's own pixels).
struct RobustSpread
{
  double centre = 0.0;
  double sigma = 0.0;
};

/// RobustSpread of `values`; centre NaN and sigma 0 when `values` is empty.
RobustSpread robustSpread(std::vector<double> values);

/// Arithmetic mean; NaN when `values` is empty.
double mean(const std::vector<double>& values);

/// CPU time of the calling thread in seconds. Unlike wall time it does not
/// grow when other processes share the cores.
double threadCpuSeconds();
}  // namespace brick_pose
