#pragma once
// The refinement methods bench_pose compares (the paper's Table 1 rows), their
// names and the estimator parameters each runs with.

#include <array>
#include <cstddef>

#include "brick_pose/pose/brick_pose_estimator.h"

namespace brick_pose
{
namespace pose_bench
{
enum class Method
{
  kNone,
  kCorrectionPaper,
  kCorrectionFull,
  kIcp,
};
constexpr std::array<Method, 4> kMethods{{Method::kNone, Method::kCorrectionPaper, Method::kCorrectionFull, Method::kIcp}};
constexpr std::size_t kMethodCount = kMethods.size();

/// Machine name (CSV, JSON): "super4pcs_only", "correction_paper", ...
const char* methodName(Method method);
/// Name in the tables and the plot.
const char* methodLabel(Method method);
/// Correction runs in microseconds, ICP in milliseconds: each is shown in its unit.
bool timedInMicroseconds(Method method);
BrickPoseEstimatorParams estimatorParamsFor(Method method);
}  // namespace pose_bench
}  // namespace brick_pose
