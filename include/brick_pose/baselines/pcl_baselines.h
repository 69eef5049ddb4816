#pragma once
// PCL 1.13 registrations wrapped in the Super4PCS API shape, as baselines for
// the benchmark: 4PCS (FPCSInitialAlignment), keypoint 4PCS
// (KFPCSInitialAlignment) and ICP started from the identity. All PCL template
// instantiations live in pcl_baselines.cpp.
//
// PCL's 4PCS implementations seed std::rand from the clock, so unlike our
// Super4PCS their results are not reproducible run to run.

#include "brick_pose/correction/icp_refinement.h"
#include "brick_pose/registration/point_set.h"
#include "brick_pose/registration/registration_result.h"

namespace brick_pose
{
namespace registration
{
struct PclFpcsParams
{
  double overlap = 0.95;  ///< setApproxOverlap
  double delta_m = 0.004;  ///< setDelta (absolute, not normalised)
  int sample_size = 200;  ///< setNumberOfSamples (source sampling)
  /// setMaxComputationTime: PCL counts whole seconds, at least 1.
  int max_time_s = 1;
  /// KFPCS only: weight of the translation term in its score.
  double kfpcs_lambda = 0.5;
  /// Bases (RANSAC iterations) to try; 0 keeps PCL's heuristic, which with
  /// the default small_error and overlap 0.95 is only about 12 bases:
  /// log(small_error) / log(1 - overlap^4) / (0.3 * 2 * overlap).
  int max_iterations = 0;
  /// Stop as soon as a candidate's fitness (1 - fraction of source points
  /// within 2 delta) falls below this; negative keeps PCL's 1 - overlap.
  double score_threshold = -1.0;

  /// Throws ConfigError naming the first unusable field.
  void validate() const;
};

/// lcp_score in the results is the fraction of source points within delta_m
/// (ICP: within max_correspondence_distance_m / 10) of a target point after
/// alignment, for comparison with Super4PCS; bases_tried and
/// candidates_verified are not reported by PCL and stay 0.
RegistrationResult alignPclFpcs(const PointSet& source, const PointSet& target, const PclFpcsParams& params);
RegistrationResult alignPclKfpcs(const PointSet& source, const PointSet& target, const PclFpcsParams& params);
RegistrationResult alignPclIcp(const PointSet& source, const PointSet& target, const IcpParams& params);
}  // namespace registration
}  // namespace brick_pose
