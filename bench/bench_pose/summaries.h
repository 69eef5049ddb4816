#pragma once
// Summaries of the recorded bricks: per method, of Super4PCS, of the
// end-to-end latency, and the groups the errors are broken down by.

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "bench_pose/records.h"

namespace brick_pose
{
namespace pose_bench
{
constexpr double kStreamRateHz = 30.0;

struct MethodSummary
{
  Method method = Method::kNone;
  int attempted = 0;
  int failed = 0;
  std::map<std::string, int> failure_reasons;
  std::vector<double> rotation_error_deg;
  std::vector<double> translation_error_mm;
  std::vector<double> refinement_us;
};

/// Strips numbers from a failure message so similar failures group together.
std::string failureGroup(const std::string& message);

/// One summary per method, in kMethods order, over the counted bricks.
std::vector<MethodSummary> summariseMethods(const std::vector<BrickRecord>& bricks);
const MethodSummary& summaryOf(const std::vector<MethodSummary>& summaries, Method method);

struct RegistrationSummary
{
  int attempted = 0;  ///< Matched, visible, complete bricks.
  int succeeded = 0;
  std::vector<double> time_ms;
  double successRate() const { return attempted ? static_cast<double>(succeeded) / attempted : std::nan(""); }
};

RegistrationSummary summariseRegistration(const std::vector<BrickRecord>& bricks);

struct LatencySummary
{
  int frames = 0;
  double p50_ms = std::nan(""), p95_ms = std::nan(""), mean_ms = std::nan("");
  double front_end_p50_ms = std::nan(""), registration_p50_ms = std::nan("");
  double sustained_rate_hz = std::nan("");
  int dropped_frames = 0;
};


LatencySummary summariseLatency(const BenchResults& results);

/// Median of one front-end measurement error over the counted bricks.
double medianMeasurement(const std::vector<BrickRecord>& bricks, double MeasurementError::*field);

/// Counted bricks split by some property (visibility, lighting, scene kind).
using GroupOf = std::string (*)(const BrickRecord&);
std::string visibilityGroup(const BrickRecord& record);
std::string lightingGroup(const BrickRecord& record);
std::string sceneGroup(const BrickRecord& record);
}  // namespace pose_bench
}  // namespace brick_pose
