#pragma once
// The real-scene half of bench_frontend: the 25 mOSD learn scenes (Kinect
// v1, 640x480) through every available mode, scored against the truth
// measured from their labels (include/brick_pose/eval/mosd_truth.h), with
// the catalogue measured from the same truth (test/data/mosd_learn/catalogue.yaml).
// The truth has no box types, so a candidate's type is not checked. A
// colour-free mode runs twice: with the table's normal as "up" (what tf
// gives a robot) and without (what a user without a gravity frame gets).

#include <string>
#include <vector>

#include "bench_frontend/cell_stats.h"
#include "bench_frontend/setup.h"

namespace brick_pose
{
namespace frontend_bench
{
struct MosdResults
{
  bool ran = false;
  std::string skipped_reason;  ///< Why not, when not run.
  int scenes = 0;
  std::string catalogue_path;
  std::size_t catalogue_types = 0;
  std::vector<CellStats> modes;  ///< In modes() order; empty stats for missing modes.
  /// Colour-free modes again without the up direction (a user without tf):
  /// in modes() order, empty for hsv and missing modes.
  std::vector<CellStats> modes_without_up;
};

MosdResults runMosd(const std::vector<ModeSpec>& modes, const Options& options);
}  // namespace frontend_bench
}  // namespace brick_pose
