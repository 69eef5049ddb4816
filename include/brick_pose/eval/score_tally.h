#pragma once
// Sums FrameMatches over a set of frames (one scene class, mode and
// resolution) into the benchmark's figures: recall of whole tops, the
// earlier benchmark's recall and precision, false complete faces by what
// they really were, and the error samples of the whole tops found.

#include <array>
#include <vector>

#include "brick_pose/eval/candidate_matching.h"

namespace brick_pose
{
namespace eval
{
struct ScoreTally
{
  int frames = 0;
  int candidates = 0;
  int complete_candidates = 0;
  int false_complete = 0;
  std::array<int, kCandidateOutcomeCount> outcomes{};
  std::array<int, kCandidateOutcomeCount> false_complete_by_outcome{};

  int whole_tops = 0;           ///< Truth tops whole in view.
  int whole_tops_found = 0;     ///< ... matched by a kWholeTop candidate.
  int whole_tops_found_complete = 0;
  /// Whole tops not found, but met by a candidate leaving their type open
  /// (TopMatch::found_type_left_open).
  int whole_tops_type_left_open = 0;
  int legacy_tops = 0;          ///< Truth tops >= legacy_min_visible_fraction visible.
  int legacy_tops_found = 0;
  int legacy_true_positives = 0;

  // One sample per kWholeTop candidate with truth geometry.
  std::vector<double> rotation_deg, normal_deg, centre_mm, length_error_mm, width_error_mm, corner_error_px;

  void add(const FrameMatch& match, double legacy_min_visible_fraction);
  void merge(const ScoreTally& other);

  /// Whole tops found over whole tops (NaN without any).
  double recall() const;
  /// The earlier benchmark's recall: tops >= 60% visible found (NaN without any).
  double legacyRecall() const;
  /// The earlier benchmark's precision: legacy true positives over candidates (NaN without any).
  double precision() const;
};
}  // namespace eval
}  // namespace brick_pose
