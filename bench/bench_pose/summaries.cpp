#include "bench_pose/summaries.h"

#include <algorithm>

#include "brick_pose/common/statistics.h"

namespace brick_pose
{
namespace pose_bench
{
namespace
{
/// Frames a single core drops on a 30 Hz stream when a frame that arrives
/// while the previous one is still being processed is discarded, replaying
/// the measured latencies in order.
int framesDroppedOnStream(const std::vector<double>& latency_ms, double rate_hz)
{
  const double period_ms = 1000.0 / rate_hz;
  double busy_until_ms = 0.0;
  int dropped = 0;
  for (std::size_t i = 0; i < latency_ms.size(); ++i)
  {
    const double arrival_ms = static_cast<double>(i) * period_ms;
    if (arrival_ms < busy_until_ms)
    {
      ++dropped;
      continue;
    }
    busy_until_ms = arrival_ms + latency_ms[i];
  }
  return dropped;
}

}  // namespace

std::string failureGroup(const std::string& message)
{
  const std::size_t digit = message.find_first_of("0123456789");
  return digit == std::string::npos ? message : message.substr(0, digit) + "...";
}

std::vector<MethodSummary> summariseMethods(const std::vector<BrickRecord>& bricks)
{
  std::vector<MethodSummary> summaries;
  for (std::size_t m = 0; m < kMethodCount; ++m)
  {
    MethodSummary summary;
    summary.method = kMethods[m];
    for (const BrickRecord& record : bricks)
    {
      if (!record.counted) continue;
      ++summary.attempted;
      const MethodOutcome& outcome = record.outcomes[m];
      if (!outcome.success)
      {
        ++summary.failed;
        ++summary.failure_reasons[failureGroup(outcome.failure)];
        continue;
      }
      summary.rotation_error_deg.push_back(outcome.rotation_error_deg);
      summary.translation_error_mm.push_back(outcome.translation_error_mm);
      summary.refinement_us.push_back(outcome.refinement_us);
    }
    summaries.push_back(summary);
  }
  return summaries;
}


const MethodSummary& summaryOf(const std::vector<MethodSummary>& summaries, Method method)
{
  return summaries[static_cast<std::size_t>(method)];
}


RegistrationSummary summariseRegistration(const std::vector<BrickRecord>& bricks)
{
  RegistrationSummary summary;
  for (const BrickRecord& record : bricks)
  {
    const bool eligible = record.counted || record.exclusion == "Super4PCS failed";
    if (!eligible) continue;
    ++summary.attempted;
    if (record.registered)
    {
      ++summary.succeeded;
      summary.time_ms.push_back(record.super4pcs_ms);
    }
  }
  return summary;
}


LatencySummary summariseLatency(const BenchResults& results)
{
  LatencySummary summary;
  summary.frames = static_cast<int>(results.latency_ms.size());
  summary.p50_ms = percentile(results.latency_ms, 0.5);
  summary.p95_ms = percentile(results.latency_ms, 0.95);
  summary.mean_ms = mean(results.latency_ms);
  summary.front_end_p50_ms = percentile(results.latency_frontend_ms, 0.5);
  summary.registration_p50_ms = percentile(results.latency_registration_ms, 0.5);
  summary.sustained_rate_hz = std::min(kStreamRateHz, 1000.0 / summary.mean_ms);
  summary.dropped_frames = framesDroppedOnStream(results.latency_ms, kStreamRateHz);
  return summary;
}

double medianMeasurement(const std::vector<BrickRecord>& bricks, double MeasurementError::*field)
{
  std::vector<double> values;
  for (const BrickRecord& record : bricks)
    if (record.counted) values.push_back(record.measurement.*field);
  return percentile(values, 0.5);
}

/// Counted bricks split by some property (visibility, lighting, scene kind).
std::string visibilityGroup(const BrickRecord& record)
{
  // 0.99 rather than 1: the face's outermost pixel row is often cut by
  // rounding even when nothing hides it.
  return record.visible_fraction >= 0.99 ? "whole top face visible" : "top face 60-99% visible";
}
std::string lightingGroup(const BrickRecord& record) { return "lighting " + sim::toString(record.lighting); }
std::string sceneGroup(const BrickRecord& record) { return "scene " + sim::toString(record.kind); }
}  // namespace pose_bench
}  // namespace brick_pose
