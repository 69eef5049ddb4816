#include "brick_pose/registration/competitor_settling.h"

#include <algorithm>

namespace brick_pose
{
namespace registration
{
namespace
{
/// Whether `pose` repeats one of `poses`.
bool repeatsAny(const Eigen::Isometry3d& pose, const std::vector<Eigen::Isometry3d>& poses,
                const CompetitorSettling& settling)
{
  for (const Eigen::Isometry3d& other : poses)
    if (settling.same(other, pose))
      return true;
  return false;
}
}  // namespace

bool polishKept(const Hypothesis& start, const Hypothesis& polished,
                const std::function<bool(const Eigen::Isometry3d&, const Eigen::Isometry3d&)>& same,
                double max_score_drop, double max_score_drop_within)
{
  const double allowed_drop = same(start.pose, polished.pose) ? max_score_drop_within : max_score_drop;
  return polished.view.combined() >= start.view.combined() - allowed_drop;
}

Comparison settleCompetitors(const std::vector<Hypothesis>& scored, const CompetitorSettling& settling)
{
  Comparison comparison;
  if (scored.empty())
    return comparison;
  const bool can_polish = static_cast<bool>(settling.polish);
  comparison.best = can_polish ? settling.polish(scored.front()) : scored.front();
  // Poses settled so far other than the best, and the starts polished so far.
  std::vector<Hypothesis> settled;
  std::vector<Eigen::Isometry3d> settled_poses;
  std::vector<Eigen::Isometry3d> polished_starts{scored.front().pose};
  for (std::size_t i = 1; i < scored.size(); ++i)
  {
    const Hypothesis& candidate = scored[i];
    if (settling.same(comparison.best.pose, candidate.pose) || repeatsAny(candidate.pose, settled_poses, settling) ||
        repeatsAny(candidate.pose, polished_starts, settling))
      continue;
    const bool close = candidate.view.combined() >= comparison.best.view.combined() - settling.min_confidence;
    if (!close || comparison.competitors_polished >= settling.max_polishes || !can_polish)
    {
      // Not settled: it counts with its fitted score (a competitor too far
      // below to matter, or one the budget of polishes leaves as it is).
      comparison.second_best = std::max(comparison.second_best, candidate.view.combined());
      if (!close)
        break;  // sorted: no later one is close either
      continue;
    }
    ++comparison.competitors_polished;
    polished_starts.push_back(candidate.pose);
    Hypothesis settled_candidate = settling.polish(candidate);
    // A polish that ended in the best's basin but not at the best may only
    // have stopped short (its radii shrink on the way from a far start):
    // once more from where it ended before the basin is called flat.
    if (settling.same(comparison.best.pose, settled_candidate.pose) &&
        !settling.agree(comparison.best.pose, settled_candidate.pose))
      settled_candidate = settling.polish(settled_candidate);
    if (settling.same(comparison.best.pose, settled_candidate.pose))
    {
      // The same basin: the same answer, unless its floor is so flat that
      // polishes from nearby starts end a good part of the tolerance apart.
      comparison.loosely_settled =
          comparison.loosely_settled || !settling.agree(comparison.best.pose, settled_candidate.pose);
      continue;
    }
    if (settled_candidate.view.combined() > comparison.best.view.combined())
      std::swap(settled_candidate, comparison.best);
    settled_poses.push_back(settled_candidate.pose);
    settled.push_back(settled_candidate);
  }
  for (const Hypothesis& other : settled)
    if (!settling.same(comparison.best.pose, other.pose))
      comparison.second_best = std::max(comparison.second_best, other.view.combined());
  return comparison;
}
}  // namespace registration
}  // namespace brick_pose
