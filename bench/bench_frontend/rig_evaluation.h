#pragma once
// The rig half of bench_frontend: every planned frame rendered at every
// resolution and run through every available mode, scored per cell.

#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "bench_frontend/cell_stats.h"
#include "bench_frontend/setup.h"
#include "brick_pose/catalogue/brick_catalogue.h"

namespace brick_pose
{
namespace frontend_bench
{
/// (scene class index, mode index, resolution index)
using CellKey = std::tuple<std::size_t, std::size_t, std::size_t>;

struct RigResults
{
  std::map<CellKey, CellStats> cells;
  /// Cells over the legacy frames only (class, mode, resolution), for the
  /// earlier benchmark's block.
  std::map<CellKey, CellStats> legacy_cells;
  std::vector<double> frame_build_ms;  ///< makeRgbdFrame at 1280x720 (hsv pass).
  /// (class, mode) pairs not run, and why (hsv on boxes without plate colours).
  std::map<std::pair<std::size_t, std::size_t>, std::string> not_applicable;
};

/// The catalogue of each class, in `classes` order (bricks: MBZIRC; boxes:
/// options.box_catalogue or config/boxes.yaml). Throws ConfigError when the
/// box catalogue cannot be read.
std::vector<BrickCatalogue> classCatalogues(const std::vector<SceneClass>& classes, const Options& options);

/// Modes run in separate passes over the same (re-rendered, bit-identical)
/// frames, so that one mode's large allocations do not disturb another's
/// timings; within a mode, resolution by resolution.
RigResults runRig(const std::vector<BrickCatalogue>& catalogues, const std::vector<SceneClass>& classes,
                  const std::vector<ModeSpec>& modes, const std::vector<Resolution>& resolutions,
                  const std::vector<FrameSpec>& plan, const Options& options);
}  // namespace frontend_bench
}  // namespace brick_pose
