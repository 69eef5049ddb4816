#include "brick_pose/eval/score_tally.h"

#include <cmath>

namespace brick_pose
{
namespace eval
{
namespace
{
double ratio(int numerator, int denominator)
{
  return denominator > 0 ? static_cast<double>(numerator) / denominator : std::nan("");
}

void append(std::vector<double>& to, const std::vector<double>& from) { to.insert(to.end(), from.begin(), from.end()); }
}  // namespace

void ScoreTally::add(const FrameMatch& match, double legacy_min_visible_fraction)
{
  ++frames;
  for (const CandidateMatch& candidate : match.candidates)
  {
    ++candidates;
    const auto outcome = static_cast<std::size_t>(candidate.outcome);
    ++outcomes[outcome];
    if (candidate.complete) ++complete_candidates;
    if (candidate.false_complete)
    {
      ++false_complete;
      ++false_complete_by_outcome[outcome];
    }
    if (candidate.legacy_true_positive) ++legacy_true_positives;
    if (!candidate.has_errors) continue;
    rotation_deg.push_back(candidate.errors.rotation_deg);
    normal_deg.push_back(candidate.errors.normal_deg);
    centre_mm.push_back(candidate.errors.centre_mm);
    length_error_mm.push_back(candidate.errors.length_error_mm);
    width_error_mm.push_back(candidate.errors.width_error_mm);
    corner_error_px.push_back(candidate.errors.corner_error_px);
  }
  for (const TopMatch& top : match.tops)
  {
    if (top.whole_in_view)
    {
      ++whole_tops;
      if (top.found) ++whole_tops_found;
      if (top.found_complete) ++whole_tops_found_complete;
      if (top.found_type_left_open) ++whole_tops_type_left_open;
    }
    if (top.visible_fraction >= legacy_min_visible_fraction)
    {
      ++legacy_tops;
      if (top.legacy_found) ++legacy_tops_found;
    }
  }
}

void ScoreTally::merge(const ScoreTally& other)
{
  // Every count and every error series, each named once.
  static constexpr int ScoreTally::*kCounts[] = {
      &ScoreTally::frames,           &ScoreTally::candidates,        &ScoreTally::complete_candidates,
      &ScoreTally::false_complete,   &ScoreTally::whole_tops,        &ScoreTally::whole_tops_found,
      &ScoreTally::whole_tops_found_complete, &ScoreTally::whole_tops_type_left_open, &ScoreTally::legacy_tops,
      &ScoreTally::legacy_tops_found,         &ScoreTally::legacy_true_positives};
  static constexpr std::vector<double> ScoreTally::*kErrorSeries[] = {
      &ScoreTally::rotation_deg,    &ScoreTally::normal_deg,     &ScoreTally::centre_mm,
      &ScoreTally::length_error_mm, &ScoreTally::width_error_mm, &ScoreTally::corner_error_px};
  for (const auto count : kCounts) this->*count += other.*count;
  for (const auto series : kErrorSeries) append(this->*series, other.*series);
  for (int k = 0; k < kCandidateOutcomeCount; ++k)
  {
    outcomes[k] += other.outcomes[k];
    false_complete_by_outcome[k] += other.false_complete_by_outcome[k];
  }
}

double ScoreTally::recall() const { return ratio(whole_tops_found, whole_tops); }
double ScoreTally::legacyRecall() const { return ratio(legacy_tops_found, legacy_tops); }
double ScoreTally::precision() const { return ratio(legacy_true_positives, candidates); }
}  // namespace eval
}  // namespace brick_pose
