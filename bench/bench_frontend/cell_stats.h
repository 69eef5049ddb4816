#pragma once
// Everything measured for one cell of the report (scene class x mode x
// resolution, or a real-scene row): the eval library's tally, the front
// end's timings, and the earlier benchmark's diagnostics (dimension and
// corner errors of tops >= 95% visible, why tops were missed, what the
// other candidates were).

#include <map>
#include <string>
#include <vector>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/eval/candidate_matching.h"
#include "brick_pose/eval/score_tally.h"
#include "brick_pose/pipeline/front_end.h"

namespace brick_pose
{
namespace frontend_bench
{
struct CellStats
{
  eval::ScoreTally tally;
  std::vector<double> total_ms, segmentation_ms, cloud_ms, roi_ms;
  std::vector<double> cpu_ms;  ///< Process CPU time of the same calls (all threads).
  // The earlier benchmark's figures, on its true positives whose top is at
  // least 95% visible: |quad length/width - truth|, |OBB extents - truth|,
  // and each quad corner's distance to the projected truth corner.
  std::vector<double> quad_dim_error_mm, obb_dim_error_mm, corner_error_px;
  /// Centre errors (mm) of the complete candidates on whole tops of their
  /// type: the faces a planner picks, placed at their catalogue size.
  std::vector<double> complete_centre_mm;
  /// How far (mm, + outward) each edge of those faces lies from the truth's
  /// edge, by what the edge was read as (EdgeKind's name): where the
  /// sensor's depth runs past the face.
  std::map<std::string, std::vector<double>> complete_edge_offset_mm;
  std::map<std::string, int> miss_reasons;            ///< Legacy tops (>= 60% visible) not found.
  std::map<std::string, int> false_positive_reasons;  ///< Candidates that are not legacy true positives.

  void merge(const CellStats& other);
};

/// Scores one frame's result into `stats`; `cpu_ms` is the process CPU time
/// of the front-end call. With `verbose`, false completes and misses go to stderr.
void recordFrame(const FrontEndResult& result, double cpu_ms, const eval::SceneTruth& truth,
                 const PinholeCamera& camera, const eval::MatchParams& match_params, bool verbose,
                 const std::string& frame_name, CellStats& stats);
}  // namespace frontend_bench
}  // namespace brick_pose
