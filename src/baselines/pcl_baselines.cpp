#include "brick_pose/baselines/pcl_baselines.h"

#include <chrono>
#include <cmath>
#include <string>

#include <pcl/registration/ia_fpcs.h>
#include <pcl/registration/ia_kfpcs.h>
#include <pcl/registration/icp.h>

#include "brick_pose/common/elapsed.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/registration/input_validation.h"
#include "brick_pose/registration/lcp_scorer.h"

namespace brick_pose
{
namespace registration
{
namespace
{
using Cloud = pcl::PointCloud<pcl::PointXYZ>;
double lcpAfter(const PointSet& source, const PointSet& target, const Eigen::Isometry3d& transform, double radius_m)
{
  const LcpScorer scorer(source.points, target.points, radius_m);
  return scorer.score(transform);
}

Eigen::Isometry3d toIsometry(const Eigen::Matrix4f& matrix)
{
  Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
  transform.matrix() = matrix.cast<double>();
  return transform;
}

using FpcsAligner = pcl::registration::FPCSInitialAlignment<pcl::PointXYZ, pcl::PointXYZ>;
using KfpcsAligner = pcl::registration::KFPCSInitialAlignment<pcl::PointXYZ, pcl::PointXYZ>;

/// Every baseline rejects bad parameters and inputs the same way before PCL
/// sees them (inside the timed run, as the results' elapsed_s always was).
template <typename Params>
void validateRun(const Params& params, const PointSet& source, const PointSet& target)
{
  params.validate();
  validateRegistrationInput(source, "source");
  validateRegistrationInput(target, "target");
}

template <typename Aligner>
void setInputs(Aligner& aligner, const PointSet& source, const PointSet& target)
{
  aligner.setInputSource(Cloud::ConstPtr(new Cloud(toPclXyz(source))));
  aligner.setInputTarget(Cloud::ConstPtr(new Cloud(toPclXyz(target))));
}

/// The result every baseline reports: PCL's transform and convergence, scored
/// like Super4PCS by the LCP within lcp_radius_m. `label` names the method in
/// the reason ("PCL converged", "PCL ICP did not converge").
template <typename Aligner>
RegistrationResult pclResult(Aligner& aligner, const PointSet& source, const PointSet& target, double lcp_radius_m,
                             const std::string& label, SteadyClock::time_point start)
{
  RegistrationResult result;
  result.source_to_target = toIsometry(aligner.getFinalTransformation());
  result.success = aligner.hasConverged();
  result.reason = label + (result.success ? " converged" : " did not converge");
  result.lcp_score = lcpAfter(source, target, result.source_to_target, lcp_radius_m);
  result.elapsed_s = secondsSince(start);
  return result;
}

/// Plain 4PCS has no setting beyond the shared ones.
void configureVariant(FpcsAligner& /*aligner*/, const PclFpcsParams& /*params*/) {}

/// Keypoint 4PCS weighs the translation in its score by lambda.
void configureVariant(KfpcsAligner& aligner, const PclFpcsParams& params)
{
  aligner.setLambda(static_cast<float>(params.kfpcs_lambda));
}

/// Runs one of PCL's 4PCS-style aligners (FPCS or KFPCS) with the shared
/// parameters; only configureVariant() differs between them.
template <typename Aligner>
RegistrationResult alignFpcsVariant(const PointSet& source, const PointSet& target, const PclFpcsParams& params)
{
  const SteadyClock::time_point start = SteadyClock::now();
  validateRun(params, source, target);
  Aligner aligner;
  configureVariant(aligner, params);
  setInputs(aligner, source, target);
  aligner.setApproxOverlap(static_cast<float>(params.overlap));
  aligner.setDelta(static_cast<float>(params.delta_m), false);
  aligner.setNumberOfSamples(params.sample_size);
  aligner.setMaxComputationTime(params.max_time_s);
  aligner.setNumberOfThreads(1);
  if (params.max_iterations > 0)
    aligner.setMaximumIterations(params.max_iterations);
  if (params.score_threshold >= 0.0)
    aligner.setScoreThreshold(static_cast<float>(params.score_threshold));
  Cloud aligned;
  aligner.align(aligned);
  return pclResult(aligner, source, target, params.delta_m, "PCL", start);
}
}  // namespace

void PclFpcsParams::validate() const
{
  const ParamCheck check("PclFpcsParams");
  check.require(overlap > 0.0 && overlap <= 1.0, "overlap", "must be in (0, 1]", overlap);
  check.require(delta_m > 0.0 && std::isfinite(delta_m), "delta_m", "must be positive", delta_m);
  check.require(sample_size >= 4, "sample_size", "must be at least 4", sample_size);
  check.require(max_time_s >= 1, "max_time_s", "must be at least 1 (PCL counts whole seconds)", max_time_s);
  check.require(max_iterations >= 0, "max_iterations", "must be >= 0 (0: PCL's heuristic)", max_iterations);
  check.require(!std::isnan(score_threshold), "score_threshold", "must be a number (negative: PCL's default)");
  check.require(kfpcs_lambda >= 0.0, "kfpcs_lambda", "must be >= 0", kfpcs_lambda);
}

RegistrationResult alignPclFpcs(const PointSet& source, const PointSet& target, const PclFpcsParams& params)
{
  return alignFpcsVariant<FpcsAligner>(source, target, params);
}

RegistrationResult alignPclKfpcs(const PointSet& source, const PointSet& target, const PclFpcsParams& params)
{
  return alignFpcsVariant<KfpcsAligner>(source, target, params);
}

RegistrationResult alignPclIcp(const PointSet& source, const PointSet& target, const IcpParams& params)
{
  const SteadyClock::time_point start = SteadyClock::now();
  validateRun(params, source, target);
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  setInputs(icp, source, target);
  icp.setMaxCorrespondenceDistance(params.max_correspondence_distance_m);
  icp.setMaximumIterations(params.max_iterations);
  icp.setTransformationEpsilon(params.transformation_epsilon_m2);
  icp.setEuclideanFitnessEpsilon(params.relative_fitness_epsilon);
  Cloud aligned;
  icp.align(aligned);
  return pclResult(icp, source, target, 0.1 * params.max_correspondence_distance_m, "PCL ICP", start);
}
}  // namespace registration
}  // namespace brick_pose
