#include "bench_registration/outcomes.h"

#include "brick_pose/common/statistics.h"

namespace bench_registration
{
using brick_pose::percentile;

Summary summarise(const MethodStats& stats)
{
  std::vector<double> times, cpu_times, rotations, translations;
  int successes = 0;
  Summary summary;
  for (const Outcome& o : stats.outcomes)
  {
    times.push_back(o.time_ms);
    cpu_times.push_back(o.cpu_ms);
    rotations.push_back(o.rotation_deg);
    translations.push_back(o.translation_mm);
    successes += o.success ? 1 : 0;
    summary.false_successes += (o.claimed && !o.correct) ? 1 : 0;
  }
  summary.median_ms = percentile(times, 0.5);
  summary.p95_ms = percentile(times, 0.95);
  summary.median_cpu_ms = percentile(cpu_times, 0.5);
  summary.p95_cpu_ms = percentile(cpu_times, 0.95);
  summary.success = stats.outcomes.empty() ? 0.0 : static_cast<double>(successes) / stats.outcomes.size();
  summary.median_rotation_deg = percentile(rotations, 0.5);
  summary.median_translation_mm = percentile(translations, 0.5);
  return summary;
}

std::pair<double, double> quantiles(const MethodStats& stats, double Outcome::*field)
{
  std::vector<double> values;
  for (const Outcome& o : stats.outcomes)
    values.push_back(o.*field);
  return {percentile(values, 0.5), percentile(values, 0.95)};
}

Outcome outcomeOf(const brick_pose::registration::RegistrationResult& result, double rotation_deg,
                  double translation_mm)
{
  Outcome outcome;
  outcome.time_ms = result.elapsed_s * 1e3;
  outcome.rotation_deg = rotation_deg;
  outcome.translation_mm = translation_mm;
  outcome.correct = rotation_deg < kSuccessRotationDeg && translation_mm < 1e3 * kSuccessTranslationM;
  outcome.claimed = result.success;
  outcome.confidence = result.confidence;
  outcome.search_cpu_ms = 1e3 * result.search_cpu_s;
  outcome.refine_cpu_ms = 1e3 * result.refine_cpu_s;
  return outcome;
}
}  // namespace bench_registration
