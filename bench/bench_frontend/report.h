#pragma once
// bench_frontend's report: the earlier benchmark's block (its figures kept,
// so old and new runs compare), the table per scene class x mode x
// resolution with the real-scene rows beside the rig's, what the false
// complete faces were, and the JSON line.

#include <string>
#include <vector>

#include "bench_frontend/mosd_evaluation.h"
#include "bench_frontend/rig_evaluation.h"
#include "bench_frontend/setup.h"

namespace brick_pose
{
namespace frontend_bench
{
struct RunInfo
{
  Options options;
  std::vector<SceneClass> classes;
  std::vector<ModeSpec> modes;
  std::vector<Resolution> resolutions;
  std::size_t planned_frames = 0;
};

/// The earlier benchmark's output for the legacy frames at 1280x720.
void printLegacyBlock(const RunInfo& run, const RigResults& rig);

/// The per-cell table, real-scene rows included, and the false-complete breakdown.
void printTables(const RunInfo& run, const RigResults& rig, const MosdResults& mosd);

/// One JSON line: the earlier benchmark's keys, then issue 10's.
std::string jsonLine(const RunInfo& run, const RigResults& rig, const MosdResults& mosd);
}  // namespace frontend_bench
}  // namespace brick_pose
