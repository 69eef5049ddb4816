#pragma once
// The outcome of one global registration, shared by Super4PCS and the PCL
// baselines so that the benchmark and the tools treat them alike.

#include <string>

#include <Eigen/Geometry>

#include "brick_pose/registration/view_score.h"

namespace brick_pose
{
namespace registration
{
struct RegistrationResult
{
  /// Maps source points onto the target: p_target = source_to_target * p_source.
  Eigen::Isometry3d source_to_target = Eigen::Isometry3d::Identity();
  /// Largest-common-pointset score: fraction (0..1) of sampled source points
  /// whose nearest target point lies within the accuracy delta.
  double lcp_score = 0.0;
  int bases_tried = 0;
  int candidates_verified = 0;
  double elapsed_s = 0.0;
  /// Thread CPU time of the congruent-set search and of the local refinement
  /// (Super4PCS only; 0 elsewhere). The rest of the CPU time of a call is
  /// setup: sampling, scales and the LCP grid. For profiling, not control.
  double search_cpu_s = 0.0;
  double refine_cpu_s = 0.0;
  /// How sure the registration is: the margin (0..1) of the best pose's
  /// score over the best pose that is not the same up to a true symmetry of
  /// the model. Whole-view mode: combined view scores (ViewScore::combined);
  /// face mode: LCP scores of the face's near-symmetric alternatives (the
  /// in-plane quarter turns), for information only. 0 when not assessed.
  double confidence = 0.0;
  double second_best_score = 0.0;
  /// Whole-view mode only (view_checked): the view checks of the result.
  bool view_checked = false;
  ViewScore view;
  /// Motions of the model onto itself found (1: none but the identity).
  int true_symmetries = 1;
  bool success = false;
  /// Why the search stopped ("good enough LCP reached", "time budget
  /// exhausted", ...) or why it failed.
  std::string reason;
};
}  // namespace registration
}  // namespace brick_pose
