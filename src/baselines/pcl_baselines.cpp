#include "brick_pose/baselines/pcl_baselines.h"

#include <chrono>
#include <cmath>

#include <pcl/registration/ia_fpcs.h>
#include <pcl/registration/ia_kfpcs.h>
#include <pcl/registration/icp.h>

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
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

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

/// Runs a configured PCL 4PCS-style aligner and fills the shared result.
template <typename Aligner>
RegistrationResult runFpcs(Aligner& aligner, const PointSet& source, const PointSet& target,
                           const PclFpcsParams& params, Clock::time_point start)
{
  aligner.setInputSource(Cloud::ConstPtr(new Cloud(toPclXyz(source))));
  aligner.setInputTarget(Cloud::ConstPtr(new Cloud(toPclXyz(target))));
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

  RegistrationResult result;
  result.source_to_target = toIsometry(aligner.getFinalTransformation());
  result.success = aligner.hasConverged();
  result.reason = result.success ? "PCL converged" : "PCL did not converge";
  result.lcp_score = lcpAfter(source, target, result.source_to_target, params.delta_m);
  result.elapsed_s = secondsSince(start);
  return result;
}
}  // namespace

void PclFpcsParams::validate() const
{
  if (!(overlap > 0.0 && overlap <= 1.0))
    throw ConfigError("PclFpcsParams.overlap must be in (0, 1], got " + std::to_string(overlap));
  if (!(delta_m > 0.0 && std::isfinite(delta_m)))
    throw ConfigError("PclFpcsParams.delta_m must be positive, got " + std::to_string(delta_m));
  if (sample_size < 4)
    throw ConfigError("PclFpcsParams.sample_size must be at least 4, got " + std::to_string(sample_size));
  if (max_time_s < 1)
    throw ConfigError("PclFpcsParams.max_time_s must be at least 1 (PCL counts whole seconds), got " +
                      std::to_string(max_time_s));
  if (max_iterations < 0)
    throw ConfigError("PclFpcsParams.max_iterations must be >= 0 (0: PCL's heuristic), got " +
                      std::to_string(max_iterations));
  if (std::isnan(score_threshold))
    throw ConfigError("PclFpcsParams.score_threshold must be a number (negative: PCL's default)");
  if (!(kfpcs_lambda >= 0.0))
    throw ConfigError("PclFpcsParams.kfpcs_lambda must be >= 0, got " + std::to_string(kfpcs_lambda));
}

RegistrationResult alignPclFpcs(const PointSet& source, const PointSet& target, const PclFpcsParams& params)
{
  const Clock::time_point start = Clock::now();
  params.validate();
  validateRegistrationInput(source, "source");
  validateRegistrationInput(target, "target");
  pcl::registration::FPCSInitialAlignment<pcl::PointXYZ, pcl::PointXYZ> aligner;
  return runFpcs(aligner, source, target, params, start);
}

RegistrationResult alignPclKfpcs(const PointSet& source, const PointSet& target, const PclFpcsParams& params)
{
  const Clock::time_point start = Clock::now();
  params.validate();
  validateRegistrationInput(source, "source");
  validateRegistrationInput(target, "target");
  pcl::registration::KFPCSInitialAlignment<pcl::PointXYZ, pcl::PointXYZ> aligner;
  aligner.setLambda(static_cast<float>(params.kfpcs_lambda));
  return runFpcs(aligner, source, target, params, start);
}

RegistrationResult alignPclIcp(const PointSet& source, const PointSet& target, const IcpParams& params)
{
  const Clock::time_point start = Clock::now();
  params.validate();
  validateRegistrationInput(source, "source");
  validateRegistrationInput(target, "target");
  pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> icp;
  icp.setInputSource(Cloud::ConstPtr(new Cloud(toPclXyz(source))));
  icp.setInputTarget(Cloud::ConstPtr(new Cloud(toPclXyz(target))));
  icp.setMaxCorrespondenceDistance(params.max_correspondence_distance_m);
  icp.setMaximumIterations(params.max_iterations);
  icp.setTransformationEpsilon(params.transformation_epsilon_m2);
  icp.setEuclideanFitnessEpsilon(params.relative_fitness_epsilon);
  Cloud aligned;
  icp.align(aligned);

  RegistrationResult result;
  result.source_to_target = toIsometry(icp.getFinalTransformation());
  result.success = icp.hasConverged();
  result.reason = result.success ? "PCL ICP converged" : "PCL ICP did not converge";
  result.lcp_score = lcpAfter(source, target, result.source_to_target, 0.1 * params.max_correspondence_distance_m);
  result.elapsed_s = secondsSince(start);
  return result;
}
}  // namespace registration
}  // namespace brick_pose
