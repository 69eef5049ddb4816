#pragma once
// PCL's FPCS and KFPCS at several settings on the first faces: the fair
// comparison is PCL at the setting closest to our success.

#include <map>
#include <string>
#include <vector>

#include "bench_registration/face_cases.h"
#include "bench_registration/outcomes.h"
#include "brick_pose/baselines/pcl_baselines.h"

namespace bench_registration
{
/// One configuration of a PCL 4PCS baseline in the sweep.
struct SweepSetting
{
  std::string label;
  brick_pose::registration::PclFpcsParams params;
};

struct SweepRow
{
  std::string method;
  std::string label;
  MethodStats stats;
};

using PclAlign = brick_pose::registration::RegistrationResult (*)(const brick_pose::registration::PointSet&,
                                                                  const brick_pose::registration::PointSet&,
                                                                  const brick_pose::registration::PclFpcsParams&);

/// The PCL settings tried: the shared one (PCL's heuristic gives
/// about 12 bases at overlap 0.95), explicit base counts, and a lower
/// overlap, whose heuristic draws more bases but also stops at a looser
/// score (1 - overlap).
std::vector<SweepSetting> sweepSettings(const brick_pose::registration::PclFpcsParams& shared, int time_s);

/// Runs one PCL method at every setting on the given faces.
std::vector<SweepRow> runSweep(const std::string& method, PclAlign align, const std::vector<SweepSetting>& settings,
                               const std::vector<FaceSample>& faces,
                               const std::map<std::string, brick_pose::registration::PointSet>& models);

/// The row that matches `our_success`: the fastest (median wall time) of
/// those at least as successful, or else the most successful one.
/// `reaches` tells which of the two it is.
const SweepRow* matchedRow(const std::vector<SweepRow>& rows, double our_success, bool& reaches);
}  // namespace bench_registration
