#pragma once
// One registration judged against ground truth, and the statistics of many.

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/registration_result.h"

namespace bench_registration
{
constexpr double kSuccessRotationDeg = 5.0;
constexpr double kSuccessTranslationM = 0.010;

struct Outcome
{
  double time_ms = 0.0;
  double cpu_ms = 0.0;
  double rotation_deg = 0.0;
  double translation_mm = 0.0;
  /// The pose is right (within the success bounds, modulo symmetry).
  bool correct = false;
  /// The method said it succeeded (for Super4PCS, result.success).
  bool claimed = false;
  /// Counted success. Face cases: the pose is right (whatever was claimed,
  /// as before). View cases: right and claimed.
  bool success = false;
  double confidence = 0.0;
  // Super4PCS's CPU profile: congruent-set search, local refinement, and the
  // rest of the call (sampling, scales, grids).
  double search_cpu_ms = 0.0;
  double refine_cpu_ms = 0.0;
  double setup_cpu_ms = 0.0;
};

struct MethodStats
{
  std::string name;
  std::string json_key;
  std::vector<Outcome> outcomes;
};

struct Summary
{
  double median_ms = 0.0, p95_ms = 0.0, median_cpu_ms = 0.0, p95_cpu_ms = 0.0, success = 0.0;
  double median_rotation_deg = 0.0, median_translation_mm = 0.0;
  int false_successes = 0;  ///< claimed and wrong
};

Summary summarise(const MethodStats& stats);

/// Median and p95 of one field over the outcomes.
std::pair<double, double> quantiles(const MethodStats& stats, double Outcome::*field);

/// Fills the error, time and claim fields of an outcome from a result, the
/// estimate already reduced to the pose error by the caller.
Outcome outcomeOf(const brick_pose::registration::RegistrationResult& result, double rotation_deg,
                  double translation_mm);
}  // namespace bench_registration
