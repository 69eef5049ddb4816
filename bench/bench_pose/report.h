#pragma once
// bench_pose's outputs: the markdown table (pose_table.md), the per-brick
// CSV, the CDF plot and the JSON line.

#include <string>
#include <vector>

#include "bench_pose/records.h"
#include "bench_pose/summaries.h"

namespace brick_pose
{
namespace pose_bench
{
/// What the run was, for the report's first line and the JSON line.
struct RunDescription
{
  int frames = 0;
  std::uint64_t seed = 0;
  std::string resolution = "1280x720";
  int max_pile_bricks = 6;  ///< unorganised piles draw 2..this
};

std::string markdownTable(const BenchResults& results, const std::vector<MethodSummary>& summaries,
                          const RegistrationSummary& registration, const LatencySummary& latency,
                          const RunDescription& run);
void writeCsv(const std::string& path, const std::vector<BrickRecord>& bricks);
/// Empirical CDFs of the rotation and translation errors, one curve per method.
void writePlot(const std::string& path, const std::vector<MethodSummary>& summaries);
std::string jsonSummary(const BenchResults& results, const std::vector<MethodSummary>& summaries,
                        const RegistrationSummary& registration, const LatencySummary& latency,
                        const RunDescription& run);
}  // namespace pose_bench
}  // namespace brick_pose
