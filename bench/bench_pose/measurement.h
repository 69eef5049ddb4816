#pragma once
// Matching a candidate to the rig's truth and the errors of the front end's
// measurements that the correction works from.

#include <string>

#include "bench_pose/records.h"
#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/sim/synthetic_rig.h"

namespace brick_pose
{
namespace pose_bench
{
/// The truth brick whose top face holds most of the candidate's pixels (at
/// least half), if of the candidate's type; the reason otherwise. Not the
/// brick under the candidate's centre pixel: a plate with another brick lying
/// across its middle is measured whole from its two visible ends, and its
/// centre pixel then shows the brick on top.
const sim::BrickTruth* matchTruth(const BrickCandidate& candidate, const sim::SyntheticFrame& frame,
                                  std::string& reason);

MeasurementError measurementErrorOf(const BrickCandidate& candidate, const sim::BrickTruth& truth,
                                    const PinholeCamera& camera);

/// Why a matched brick does not count toward the accuracy table, or "".
std::string exclusionReason(const BrickCandidate& candidate, const sim::BrickTruth& truth, bool duplicate);
}  // namespace pose_bench
}  // namespace brick_pose
