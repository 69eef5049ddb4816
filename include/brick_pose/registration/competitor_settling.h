#pragma once
// The last step of the whole-view search (whole_view_registration.cpp): the
// best fitted pose hypothesis against its competitors. Coverage scores change
// slowly when a pose slides along a long face (by offset / length), so a pose
// a few centimetres along from the best one scores nearly as well without
// being another answer: it lies in the same basin. A competitor within the
// confidence margin is therefore polished too (the polish's boundary stage
// sees the ends of faces); when it settles on the best pose it is the same
// answer, when it settles elsewhere with a close score the view is
// ambiguous, and when it settles elsewhere with a better score it becomes
// the best.

#include <functional>
#include <vector>

#include <Eigen/Geometry>

#include "brick_pose/registration/view_score.h"

namespace brick_pose
{
namespace registration
{
struct Hypothesis
{
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< model -> target
  double target_coverage = 0.0;  ///< the search's quick score
  ViewScore view;
  bool view_evaluated = false;
};

struct Comparison
{
  Hypothesis best;
  double second_best = 0.0;  ///< combined score of the best distinct pose
  /// A competitor settled on the best pose only as the same hypothesis, not
  /// within the settled agreement: the view does not fix the position to the
  /// accuracy claimed.
  bool loosely_settled = false;
  /// Competitors polished (the best itself not counted).
  int competitors_polished = 0;
};

struct CompetitorSettling
{
  /// The local polish of a hypothesis (returns it polished and scored).
  std::function<Hypothesis(const Hypothesis&)> polish;
  /// Whether two poses are one hypothesis (modulo the model's symmetries).
  std::function<bool(const Eigen::Isometry3d&, const Eigen::Isometry3d&)> same;
  /// Whether two polishes of one hypothesis agree to the claimed accuracy.
  std::function<bool(const Eigen::Isometry3d&, const Eigen::Isometry3d&)> agree;
  /// Competitors within this of the best's combined score are polished.
  double min_confidence = 0.08;
  /// Most competitors polished (each costs about one polish); with 0, or no
  /// polish, they all count with their fitted scores.
  int max_polishes = 3;
};

/// Whether a polish of `start` that ended at `polished` is kept. Within one
/// hypothesis (`same`) the polish is the finer judge and may lose up to
/// max_score_drop_within of the combined score: coverage scores at the match
/// radius change by offset / length along a long face and with the erosion
/// of grazing faces, and a polish that moved the pose by less than the
/// hypothesis tolerance refined it (view 27 of the whole-view bench: 11.9 ->
/// 1.0 mm from the truth, at a combined score 0.032 lower). A larger loss is
/// a polish that went astray even inside the tolerance (a box pose tilted
/// 6.6 deg, 0.25 lower), and one that left the hypothesis may lose at most
/// max_score_drop (more means it was pulled off by clutter): the start is
/// kept.
bool polishKept(const Hypothesis& start, const Hypothesis& polished,
                const std::function<bool(const Eigen::Isometry3d&, const Eigen::Isometry3d&)>& same,
                double max_score_drop, double max_score_drop_within);

/// The best of the fitted hypotheses (`scored`, best combined score first),
/// polished, and the score of its strongest distinct competitor. A candidate
/// that repeats a start already polished (the search and the alternatives
/// often find one pose twice) lies in a basin already settled and spends no
/// polish of the budget. A competitor whose polish ends in the best's basin
/// but not within `agree` of the best is polished once more from there before
/// the view is called loose: from a far start the polish's shrinking radii can
/// stop it short.
Comparison settleCompetitors(const std::vector<Hypothesis>& scored, const CompetitorSettling& settling);
}  // namespace registration
}  // namespace brick_pose
