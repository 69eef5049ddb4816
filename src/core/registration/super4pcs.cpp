#include "brick_pose/registration/super4pcs.h"

#include <chrono>
#include <cmath>
#include <random>
#include <sstream>

#include <time.h>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/number_text.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/registration/congruent_set_finder.h"
#include "brick_pose/registration/coplanar_base.h"
#include "brick_pose/registration/icp_polish.h"
#include "brick_pose/registration/input_validation.h"
#include "brick_pose/registration/lcp_scorer.h"
#include "brick_pose/registration/point_grid.h"
#include "brick_pose/registration/rigid_fit.h"
#include "brick_pose/registration/shell_pair_index.h"
#include "brick_pose/registration/strided_deadline.h"
#include "brick_pose/registration/uniform_sampling.h"
#include "brick_pose/registration/whole_view_registration.h"

namespace brick_pose
{
namespace registration
{
namespace
{
// Consecutive failed base draws after which the source is declared unusable
// (e.g. nearly collinear within the tolerances).
constexpr int kMaxBaseDrawFailures = 8;
// LCP radius over the target's median point spacing: a spot on a regularly
// sampled surface is within 0.71 spacings of a point; the rest is for noise.
constexpr double kLcpRadiusPerSpacing = 1.3;
// Candidates verified between two looks at the clock.
constexpr int kClockStride = 32;

// Scores and fractions in reasons read to three digits.
std::string formatScore(double value) { return numberText(value, 3); }



/// The target's normals need not be unit length here.
bool normalsMapped(const Eigen::Isometry3d& transform, const CoplanarBase& base, const PointSet& target,
                   const CongruentSet& set, double max_angle_rad)
{
  return baseNormalsMapped(
      transform, base, [&](int k) { return target.normals[set[k]].normalized(); }, max_angle_rad);
}
/// The samples the search works on and the scales derived from them.
struct SearchInput
{
  PointSet source_sample;
  PointSet target_sample;
  bool use_normals = false;
  SearchScales scales;
};

/// The best candidate of the search and why the search stopped.
struct SearchOutcome
{
  double best_score = -1.0;  ///< negative when no candidate passed the fit
  Eigen::Isometry3d best_transform = Eigen::Isometry3d::Identity();
  std::string stop_reason;
};

SearchScales measureScales(const PointSet& source_sample, const PointSet& target_sample, const PointSet& target,
                           const Super4PCSParams& params, std::mt19937_64& rng)
{
  SearchScales scales;
  // A base point's counterpart in the target sample is up to about half the
  // sample spacing away, so tolerances finer than that would miss true sets.
  scales.target_sample_spacing_m = neighbourSpacing(target_sample.points, 0.5, rng);
  scales.pair_tolerance_m = std::max(params.delta_m, 0.5 * scales.target_sample_spacing_m);
  // The LCP radius must let almost every source point that lies on the
  // target's surface find a target point, or the score of the right pose
  // depends on sampling luck (and maximising it favours poses that happen to
  // interlock the two samplings). A multiple of the median rather than a high
  // quantile: outliers have far neighbours and would inflate a quantile.
  scales.lcp_radius_m = std::max(params.delta_m, kLcpRadiusPerSpacing * neighbourSpacing(target.points, 0.5, rng));
  scales.source_diameter_m = approximateDiameter(source_sample.points, rng);
  return scales;
}

CongruenceTolerances tolerancesFor(const CoplanarBase& base, const SearchScales& scales,
                                   const Super4PCSParams& params)
{
  CongruenceTolerances tolerances;
  tolerances.distance_m = scales.pair_tolerance_m;
  tolerances.normal_rad = params.max_normal_difference_deg * kDegToRad;
  // A pair direction is known to about twice the tolerance over its length.
  tolerances.angle_rad = params.max_angle_difference_deg > 0.0
                             ? params.max_angle_difference_deg * kDegToRad
                             : std::atan(2.0 * scales.pair_tolerance_m / std::min(base.r1_m(), base.r2_m()));
  return tolerances;
}

/// Draws bases and verifies their congruent sets until the LCP is good
/// enough, the bases run out or the time budget is spent. Counts bases and
/// verified candidates into `result`.
SearchOutcome searchCongruentSets(const SearchInput& input, const LcpScorer& scorer, const Super4PCSParams& params,
                                  SteadyClock::time_point start, std::mt19937_64& rng, RegistrationResult& result)
{
  const ShellPairIndex pair_index(input.target_sample.points, input.scales.pair_tolerance_m);
  const CongruentSetFinder finder(input.target_sample, pair_index);
  BaseSelectionLimits limits;
  limits.max_diameter_m = params.overlap * input.scales.source_diameter_m;
  limits.coplanar_tolerance_m = 0.5 * input.scales.pair_tolerance_m;
  const double stop_score = params.good_enough_ratio * params.overlap;
  const double max_fit_rms_m = params.max_fit_rms_factor * input.scales.pair_tolerance_m;

  SearchOutcome outcome;
  int base_draw_failures = 0;
  std::vector<Eigen::Vector3d> base_points(4);
  std::vector<Eigen::Vector3d> set_points(4);
  while (outcome.stop_reason.empty())
  {
    if (result.bases_tried >= params.max_bases)
    {
      outcome.stop_reason = "all " + std::to_string(params.max_bases) + " bases tried";
      break;
    }
    if (secondsSince(start) >= params.max_time_s)
    {
      outcome.stop_reason = "time budget exhausted";
      break;
    }
    const std::optional<CoplanarBase> base = drawCoplanarBase(input.source_sample, limits, rng);
    if (!base)
    {
      if (++base_draw_failures >= kMaxBaseDrawFailures)
        outcome.stop_reason = "no wide coplanar 4-point base found in the source";
      continue;
    }
    base_draw_failures = 0;
    ++result.bases_tried;
    const CongruenceTolerances tolerances = tolerancesFor(*base, input.scales, params);
    for (int k = 0; k < 4; ++k)
      base_points[k] = base->points[k];

    StridedDeadline deadline(start, params.max_time_s, kClockStride);
    finder.find(*base, tolerances, [&](const CongruentSet& set) {
      if (deadline.passed())
      {
        outcome.stop_reason = "time budget exhausted";
        return false;
      }
      for (int k = 0; k < 4; ++k)
        set_points[k] = input.target_sample.points[set[k]];
      const RigidFit fit = fitRigid(base_points, set_points);
      if (!fit.valid || fit.rms_m > max_fit_rms_m)
        return true;
      if (input.use_normals && !normalsMapped(fit.transform, *base, input.target_sample, set, tolerances.normal_rad))
        return true;
      ++result.candidates_verified;
      const double score = scorer.score(fit.transform, outcome.best_score);
      if (score > outcome.best_score)
      {
        outcome.best_score = score;
        outcome.best_transform = fit.transform;
      }
      if (outcome.best_score >= stop_score)
      {
        outcome.stop_reason = "good-enough LCP reached";
        return false;
      }
      return true;
    });
  }
  return outcome;
}

}  // namespace

void Super4PCSParams::validate() const
{
  const ParamCheck check("Super4PCSParams");
  check.require(overlap > 0.0 && overlap <= 1.0, "overlap", "must be in (0, 1]", overlap);
  // Below a micrometre no sensor is that accurate and grid indices would
  // lose their meaning.
  check.inRange(delta_m, 1e-6, 1e3, "delta_m");
  check.require(sample_size >= 4, "sample_size", "must be at least 4", sample_size);
  check.require(lcp_sample_size >= 1, "lcp_sample_size", "must be at least 1", lcp_sample_size);
  check.inRange(max_normal_difference_deg, 0.0, 180.0, "max_normal_difference_deg");
  check.inRange(max_angle_difference_deg, 0.0, 180.0, "max_angle_difference_deg");
  check.require(max_time_s > 0.0, "max_time_s", "must be positive", max_time_s);
  check.require(max_bases >= 1, "max_bases", "must be at least 1", max_bases);
  check.inRange(good_enough_ratio, 0.0, 1.0, "good_enough_ratio");
  check.inRange(min_success_ratio, 0.0, 1.0, "min_success_ratio");
  check.require(max_fit_rms_factor > 0.0, "max_fit_rms_factor", "must be positive", max_fit_rms_factor);
  check.require(refine_sample_size >= 3, "refine_sample_size", "must be at least 3", refine_sample_size);
  check.require(refine_source_sample_size >= 3, "refine_source_sample_size", "must be at least 3",
                refine_source_sample_size);
  check.require(refine_iterations >= 0, "refine_iterations", "must be >= 0", refine_iterations);
  check.require(fine_refine_iterations >= 0, "fine_refine_iterations", "must be >= 0", fine_refine_iterations);
  check.require(fine_refine_sample_size >= 3, "fine_refine_sample_size", "must be at least 3",
                fine_refine_sample_size);
  check.require(fine_refine_source_sample_size >= 3, "fine_refine_source_sample_size", "must be at least 3",
                fine_refine_source_sample_size);
  view.validate();
}

void ViewRegistrationParams::validate() const
{
  const ParamCheck check("Super4PCSParams.view");
  check.require(viewpoint_m.allFinite(), "viewpoint_m", "must be finite");
  check.require(scan_sample_size >= 8, "scan_sample_size", "must be at least 8", scan_sample_size);
  check.require(model_sample_size >= 8, "model_sample_size", "must be at least 8", model_sample_size);
  check.require(max_candidates >= 1, "max_candidates", "must be at least 1", max_candidates);
  check.require(kept_hypotheses >= 1, "kept_hypotheses", "must be at least 1", kept_hypotheses);
  check.inRange(max_normal_difference_deg, 1.0, 90.0, "max_normal_difference_deg");
  check.inRange(min_visible_cos, 0.0, 1.0, "min_visible_cos");
  check.inRange(free_space_margin_m, 0.0, 1e3, "free_space_margin_m");
  check.inRange(max_relative_surface_variation, 1.0, 1e3, "max_relative_surface_variation");
  check.inRange(min_sight_cos, 0.0, 1.0, "min_sight_cos");
  check.inRange(normal_radius_per_range, 0.0, 1.0, "normal_radius_per_range");
  check.inRange(min_target_coverage, 0.0, 1.0, "min_target_coverage");
  check.inRange(min_model_coverage, 0.0, 1.0, "min_model_coverage");
  check.inRange(max_free_space_violation, 0.0, 1.0, "max_free_space_violation");
  check.inRange(min_confidence, 0.0, 1.0, "min_confidence");
  check.inRange(stop_target_coverage, 0.0, 1.0, "stop_target_coverage");
}

Super4PCS::Super4PCS(const Super4PCSParams& params) : params_(params)
{
  params_.validate();
}

RegistrationResult Super4PCS::align(const PointSet& source, const PointSet& target) const
{
  const SteadyClock::time_point start = SteadyClock::now();
  validateRegistrationInput(source, "source");
  validateRegistrationInput(target, "target");
  if (params_.view.mode == ViewMode::kOn || (params_.view.mode == ViewMode::kAuto && isMultiFaceModel(source)))
    return alignWholeView(source, target, params_);

  std::mt19937_64 rng(params_.seed);
  SearchInput input;
  input.source_sample = source.subset(uniformSubsample(source.points, params_.sample_size, rng));
  input.target_sample = target.subset(uniformSubsample(target.points, params_.sample_size, rng));
  input.use_normals = source.hasNormals() && target.hasNormals();
  if (!input.use_normals)
  {
    input.source_sample.normals.clear();
    input.target_sample.normals.clear();
  }
  const std::vector<Eigen::Vector3d> lcp_sample =
      source.subset(uniformSubsample(source.points, params_.lcp_sample_size, rng)).points;
  input.scales = measureScales(input.source_sample, input.target_sample, target, params_, rng);
  const LcpScorer scorer(lcp_sample, target.points, input.scales.lcp_radius_m);

  RegistrationResult result;
  const double search_cpu_start_s = threadCpuSeconds();
  SearchOutcome search = searchCongruentSets(input, scorer, params_, start, rng, result);
  result.search_cpu_s = threadCpuSeconds() - search_cpu_start_s;
  result.reason = search.stop_reason;
  if (search.best_score < 0.0)
  {
    result.success = false;
    result.reason += "; no congruent 4-point set found";
    result.elapsed_s = secondsSince(start);
    return result;
  }
  if (params_.refine_iterations > 0)
  {
    const double refine_cpu_start_s = threadCpuSeconds();
    const Eigen::Isometry3d refined =
        polishWithIcp(source, target, search.best_transform, input.scales, params_, start, rng);
    if (refinementKeepsCoverage(lcp_sample, target.points, input.scales.lcp_radius_m, search.best_transform, refined))
    {
      search.best_transform = refined;
      search.best_score = scorer.score(refined);
    }
    result.refine_cpu_s = threadCpuSeconds() - refine_cpu_start_s;
  }
  result.source_to_target = search.best_transform;
  result.lcp_score = search.best_score;
  const double accept_score = params_.min_success_ratio * params_.overlap;
  result.success = search.best_score >= accept_score;
  if (!result.success)
    result.reason +=
        "; best LCP " + formatScore(search.best_score) + " below the acceptance " + formatScore(accept_score);
  result.elapsed_s = secondsSince(start);
  return result;
}

RegistrationResult alignSuper4PCS(const pcl::PointCloud<pcl::PointXYZ>& source,
                                  const pcl::PointCloud<pcl::PointXYZ>& target, const Super4PCSParams& params)
{
  return Super4PCS(params).align(fromPcl(source), fromPcl(target));
}

RegistrationResult alignSuper4PCS(const pcl::PointCloud<pcl::PointNormal>& source,
                                  const pcl::PointCloud<pcl::PointNormal>& target, const Super4PCSParams& params)
{
  return Super4PCS(params).align(fromPcl(source), fromPcl(target));
}
}  // namespace registration
}  // namespace brick_pose
