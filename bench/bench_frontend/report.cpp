#include "bench_frontend/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>

#include "brick_pose/common/statistics.h"
#include "common/report_format.h"
#include "common/run_environment.h"

namespace brick_pose
{
namespace frontend_bench
{
namespace
{
using bench::formatted;

std::size_t legacyResolution(const RunInfo& run)
{
  for (std::size_t r = 0; r < run.resolutions.size(); ++r)
    if (run.resolutions[r].legacy) return r;
  return 0;
}

std::size_t modeIndex(const RunInfo& run, const std::string& name)
{
  for (std::size_t m = 0; m < run.modes.size(); ++m)
    if (run.modes[m].name == name) return m;
  return run.modes.size();
}

constexpr std::size_t kAny = std::numeric_limits<std::size_t>::max();

/// Cells of `cells` matching the filters (kAny: any), merged.
CellStats mergedCells(const std::map<CellKey, CellStats>& cells, std::size_t scene_class, std::size_t mode,
                      std::size_t resolution)
{
  CellStats merged;
  for (const auto& [key, stats] : cells)
  {
    const auto [c, m, r] = key;
    if ((scene_class == kAny || c == scene_class) && (mode == kAny || m == mode) &&
        (resolution == kAny || r == resolution))
      merged.merge(stats);
  }
  return merged;
}

void printLegacyMode(const std::string& name, const CellStats& stats)
{
  const eval::ScoreTally& tally = stats.tally;
  std::printf("\n== %s ==\n", name.c_str());
  std::printf("  recall     %6.4f  (%d / %d top faces >= 60%% visible)\n", tally.legacyRecall(),
              tally.legacy_tops_found, tally.legacy_tops);
  std::printf("  precision  %6.4f  (%d / %d candidates)\n", tally.precision(), tally.legacy_true_positives,
              tally.candidates);
  std::printf("  dims error median  quad %.2f mm   obb %.2f mm   (n = %zu)\n", percentile(stats.quad_dim_error_mm, 0.5),
              percentile(stats.obb_dim_error_mm, 0.5), stats.quad_dim_error_mm.size());
  std::printf("  corner error px    median %.3f  p90 %.3f  (n = %zu)\n", percentile(stats.corner_error_px, 0.5),
              percentile(stats.corner_error_px, 0.9), stats.corner_error_px.size());
  std::printf("  time ms per frame  p50 %.2f  p95 %.2f  mean %.2f  (wall)\n", percentile(stats.total_ms, 0.5),
              percentile(stats.total_ms, 0.95), mean(stats.total_ms));
  std::printf("  cpu ms per frame   p50 %.2f  p95 %.2f  (process CPU time, all threads)\n", percentile(stats.cpu_ms, 0.5),
              percentile(stats.cpu_ms, 0.95));
  const double total_mean = std::max(1e-9, mean(stats.total_ms));
  std::printf("  stage share (mean) segmentation %.0f%%  cloud %.0f%%  roi %.0f%%\n",
              100.0 * mean(stats.segmentation_ms) / total_mean, 100.0 * mean(stats.cloud_ms) / total_mean,
              100.0 * mean(stats.roi_ms) / total_mean);
  std::printf("  stage p50 ms       segmentation %.2f  cloud %.2f  roi %.2f\n", percentile(stats.segmentation_ms, 0.5),
              percentile(stats.cloud_ms, 0.5), percentile(stats.roi_ms, 0.5));
  for (const auto& [reason, count] : stats.miss_reasons) std::printf("  missed: %-50s %d\n", reason.c_str(), count);
  for (const auto& [reason, count] : stats.false_positive_reasons)
    std::printf("  false positive: %-42s %d\n", reason.c_str(), count);
}

std::string medianP95(const std::vector<double>& values, const char* format)
{
  if (values.empty()) return "-";
  return formatted(format, percentile(values, 0.5)) + " / " + formatted(format, percentile(values, 0.95));
}

std::string ratioCell(int numerator, int denominator)
{
  if (denominator == 0) return "-";
  return formatted("%.3f", static_cast<double>(numerator) / denominator) + " (" + std::to_string(numerator) + "/" +
         std::to_string(denominator) + ")";
}

/// The recall cell: whole tops found, and how many more were met with
/// their type left open.
std::string recallCell(const eval::ScoreTally& tally)
{
  const std::string found = ratioCell(tally.whole_tops_found, tally.whole_tops);
  if (tally.whole_tops_type_left_open == 0) return found;
  return found + " +" + std::to_string(tally.whole_tops_type_left_open) + " open";
}

void printRow(const std::string& scene, const std::string& mode, const std::string& resolution, const CellStats& stats)
{
  const eval::ScoreTally& tally = stats.tally;
  std::vector<double> dims = tally.length_error_mm;
  dims.insert(dims.end(), tally.width_error_mm.begin(), tally.width_error_mm.end());
  std::printf("| %s | %s | %s | %d | %s | %s | %s | %d / %d | %s | %s | %s | %s | %s |\n", scene.c_str(),
              mode.c_str(), resolution.c_str(), tally.frames, recallCell(tally).c_str(),
              ratioCell(tally.legacy_tops_found, tally.legacy_tops).c_str(),
              ratioCell(tally.legacy_true_positives, tally.candidates).c_str(), tally.false_complete,
              tally.complete_candidates, medianP95(tally.rotation_deg, "%.2f").c_str(),
              medianP95(tally.centre_mm, "%.1f").c_str(), formatted("%.1f", percentile(dims, 0.5)).c_str(),
              medianP95(stats.total_ms, "%.0f").c_str(), formatted("%.0f", percentile(stats.cpu_ms, 0.5)).c_str());
}

/// Calls `row` with each rig cell that ran (class, mode, resolution and its
/// stats), in table order; colour-free modes only when `colour_free_only`.
void forEachRigCell(const RunInfo& run, const RigResults& rig, bool colour_free_only,
                    const std::function<void(const SceneClass&, const ModeSpec&, const Resolution&,
                                             const CellStats&)>& row)
{
  for (std::size_t c = 0; c < run.classes.size(); ++c)
    for (std::size_t m = 0; m < run.modes.size(); ++m)
    {
      if (!run.classes[c].kind || !run.modes[m].mode || (colour_free_only && !run.modes[m].colour_free)) continue;
      for (std::size_t r = 0; r < run.resolutions.size(); ++r)
      {
        const CellStats stats = mergedCells(rig.cells, c, m, r);
        if (!stats.total_ms.empty()) row(run.classes[c], run.modes[m], run.resolutions[r], stats);
      }
    }
}

/// Where the colour-free modes spend a frame, per class and resolution: the
/// timing targets are on the whole front end, and this says which stage to cut.
void printStageTimes(const RunInfo& run, const RigResults& rig)
{
  std::printf("\nColour-free stage times, ms p50 (wall): segmentation / cloud / roi / total\n\n");
  std::printf("| scene class | mode | resolution | segmentation | cloud | roi | total |\n|---|---|---|---|---|---|---|\n");
  forEachRigCell(run, rig, true, [](const SceneClass& scene_class, const ModeSpec& mode, const Resolution& resolution,
                                    const CellStats& stats) {
    std::printf("| %s | %s | %s | %.1f | %.1f | %.1f | %.1f |\n", scene_class.label.c_str(), mode.name.c_str(),
                resolution.label.c_str(), percentile(stats.segmentation_ms, 0.5), percentile(stats.cloud_ms, 0.5),
                percentile(stats.roi_ms, 0.5), percentile(stats.total_ms, 0.5));
  });
}

void printBreakdown(const std::string& name, const eval::ScoreTally& tally)
{
  std::printf("- %s: %d false complete of %d complete candidates", name.c_str(), tally.false_complete,
              tally.complete_candidates);
  const char* separator = ": ";
  for (int k = 0; k < eval::kCandidateOutcomeCount; ++k)
    if (tally.false_complete_by_outcome[k] > 0)
    {
      std::printf("%s%s %d", separator, eval::toString(static_cast<eval::CandidateOutcome>(k)),
                  tally.false_complete_by_outcome[k]);
      separator = ", ";
    }
  const int uncertain = tally.outcomes[static_cast<std::size_t>(eval::CandidateOutcome::kUncertainTop)];
  if (uncertain > 0) std::printf(" (%d candidates on tops the truth cannot judge, not counted)", uncertain);
  std::printf("\n");
}

double colourFreeP50Ms(const RunInfo& run, const RigResults& rig, const std::string& resolution_label)
{
  const ModeSpec* mode = headlineColourFreeMode(run.modes);
  if (!mode) return std::nan("");
  const std::size_t m = static_cast<std::size_t>(mode - run.modes.data());
  for (std::size_t r = 0; r < run.resolutions.size(); ++r)
    if (run.resolutions[r].label == resolution_label) return percentile(mergedCells(rig.cells, kAny, m, r).total_ms, 0.5);
  return std::nan("");
}
}  // namespace

void printLegacyBlock(const RunInfo& run, const RigResults& rig)
{
  std::printf("bench_frontend: %d frames, seed %llu, 1280x720, 0.5-2 m, singles/organised/unorganised piles, "
              "normal/sunlight/low_light\n",
              run.options.frames, static_cast<unsigned long long>(run.options.seed));
  std::printf("frame build (makeRgbdFrame, 16UC1 -> metres): p50 %.2f ms (not part of the front-end time)\n",
              percentile(rig.frame_build_ms, 0.5));
  std::printf("load average (1 min) at the end: %.2f on %d cores: wall times include waiting for other processes\n",
              bench::loadAverage(), 2);
  const std::size_t r = legacyResolution(run);
  for (std::size_t m = 0; m < run.modes.size(); ++m)
    if (run.modes[m].mode) printLegacyMode(run.modes[m].name, mergedCells(rig.legacy_cells, kAny, m, r));
}

/// The centres of the complete faces alone (the table's centre column
/// holds every whole top found, partial ones too): what a planner picks.
void printCompleteCentres(const RunInfo& run, const RigResults& rig)
{
  std::printf("\nCentres of the complete faces (whole tops of their type), mm\n\n");
  std::printf("| scene class | mode | resolution | complete faces | centre mm median / p95 |\n|---|---|---|---|---|\n");
  forEachRigCell(run, rig, false, [](const SceneClass& scene_class, const ModeSpec& mode,
                                     const Resolution& resolution, const CellStats& stats) {
    if (stats.complete_centre_mm.empty()) return;
    std::printf("| %s | %s | %s | %zu | %s |\n", scene_class.label.c_str(), mode.name.c_str(),
                resolution.label.c_str(), stats.complete_centre_mm.size(),
                medianP95(stats.complete_centre_mm, "%.1f").c_str());
  });
}

/// Where the complete colour-free faces' edges lie against the truth's, by
/// what each was read as: depth-bounded edges run past the face on D4xx
/// depth, colour-placed ones do not (catalogue_size_placement.h). Measured
/// after the placement unless --measured-corners.
void printCompleteEdgeOffsets(const RunInfo& run, const RigResults& rig)
{
  const std::vector<std::pair<std::string, std::vector<EdgeKind>>> groups = {
      {"step down", {EdgeKind::kStepDown}},
      {"crease", {EdgeKind::kCrease}},
      {"line, seam, size-placed line, wall foot",
       {EdgeKind::kColourLine, EdgeKind::kSeam, EdgeKind::kSizePlacedLine, EdgeKind::kStepUp}}};
  std::printf("\nEdges of the complete colour-free faces against the truth's, mm outward, median (count)%s\n\n",
              run.options.measured_corners ? ", as measured" : ", after place_on_catalogue_size");
  std::printf("| scene class | mode | resolution | step down | crease | line, seam, size-placed line, wall foot |\n"
              "|---|---|---|---|---|---|\n");
  forEachRigCell(run, rig, true, [&groups](const SceneClass& scene_class, const ModeSpec& mode,
                                           const Resolution& resolution, const CellStats& stats) {
    if (stats.complete_edge_offset_mm.empty()) return;
    std::printf("| %s | %s | %s", scene_class.label.c_str(), mode.name.c_str(), resolution.label.c_str());
    for (const auto& [name, kinds] : groups)
    {
      std::vector<double> offsets;
      for (const EdgeKind kind : kinds)
        if (const auto found = stats.complete_edge_offset_mm.find(toString(kind));
            found != stats.complete_edge_offset_mm.end())
          offsets.insert(offsets.end(), found->second.begin(), found->second.end());
      std::printf(" | %s", offsets.empty() ? "-"
                                            : (formatted("%.1f", percentile(offsets, 0.5)) + " (" +
                                               std::to_string(offsets.size()) + ")")
                                                  .c_str());
    }
    std::printf(" |\n");
  });
}

void printTables(const RunInfo& run, const RigResults& rig, const MosdResults& mosd)
{
  std::printf("\n== Front end per scene class x mode x resolution (issue 10)\n\n");
  std::printf("Rig: %zu frames planned per mode and resolution (the %d legacy frames, then %d per further class, "
              "framed by the rig's defaults for its kind, depth model as named). "
              "Whole tops: catalogue top faces facing up whose edges the rig sees all in the image and unhidden, "
              ">= 95%% visible; recall counts a candidate "
              "holding >= 70%% of one, of its type (\"+N open\": N more met by a candidate of another type that names "
              "theirs among its other_possible_types, where only a side would tell). False complete: candidates "
              "marked complete that are not a whole top of their type. Errors on the whole tops found: face-frame rotation (mod the half turn), centre, |length|/|width|.\n\n",
              run.planned_frames, run.options.frames, std::max(1, run.options.frames / 4));
  std::printf("| scene class | mode | resolution | frames | recall (whole tops) | recall (>= 60%% visible) | precision "
              "| false complete / complete | rot deg median / p95 | centre mm median / p95 | dims mm median "
              "| time ms p50 / p95 | cpu ms p50 |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t c = 0; c < run.classes.size(); ++c)
  {
    if (!run.classes[c].kind) continue;
    for (std::size_t m = 0; m < run.modes.size(); ++m)
    {
      if (!run.modes[m].mode) continue;
      const auto not_applicable = rig.not_applicable.find({c, m});
      if (not_applicable != rig.not_applicable.end())
      {
        std::printf("| %s | %s | all | n/a: %s |  |  |  |  |  |  |  |  |  |\n", run.classes[c].label.c_str(),
                    run.modes[m].name.c_str(), not_applicable->second.c_str());
        continue;
      }
      for (std::size_t r = 0; r < run.resolutions.size(); ++r)
        printRow(run.classes[c].label, run.modes[m].name, run.resolutions[r].label,
                 mergedCells(rig.cells, c, m, r));
    }
  }
  if (mosd.ran)
    for (std::size_t m = 0; m < run.modes.size(); ++m)
    {
      if (!run.modes[m].mode) continue;
      printRow("mOSD learn (real Kinect)", run.modes[m].name, "640x480", mosd.modes[m]);
      if (run.modes[m].colour_free)
        printRow("mOSD learn (real Kinect)", run.modes[m].name + ", no up", "640x480", mosd.modes_without_up[m]);
    }

  printStageTimes(run, rig);
  printCompleteCentres(run, rig);
  printCompleteEdgeOffsets(run, rig);

  std::printf("\nNot measured yet:");
  bool any = false;
  for (const SceneClass& scene_class : run.classes)
    if (!scene_class.kind)
    {
      std::printf(" class '%s' (rig kind '%s' missing);", scene_class.label.c_str(), scene_class.rig_kind.c_str());
      any = true;
    }
  for (const ModeSpec& mode : run.modes)
    if (!mode.mode)
    {
      std::printf(" mode '%s' (front end lacks it);", mode.name.c_str());
      any = true;
    }
  if (!mosd.ran)
  {
    std::printf(" mOSD rows (%s);", mosd.skipped_reason.c_str());
    any = true;
  }
  std::printf("%s\n", any ? "" : " nothing");
  if (mosd.ran)
    std::printf("mOSD: %d scenes, catalogue %s (%zu types measured from the truth); no type check (the truth has "
                "no types); colour-free modes run with the table normal as up and without up.\n",
                mosd.scenes, mosd.catalogue_path.c_str(), mosd.catalogue_types);

  std::printf("\n== What the false complete faces were\n\n");
  for (std::size_t m = 0; m < run.modes.size(); ++m)
  {
    if (!run.modes[m].mode) continue;
    printBreakdown("rig, " + run.modes[m].name, mergedCells(rig.cells, kAny, m, kAny).tally);
    if (!mosd.ran) continue;
    printBreakdown("mOSD, " + run.modes[m].name, mosd.modes[m].tally);
    if (run.modes[m].colour_free)
      printBreakdown("mOSD, " + run.modes[m].name + " without up", mosd.modes_without_up[m].tally);
  }
}

std::string jsonLine(const RunInfo& run, const RigResults& rig, const MosdResults& mosd)
{
  const std::size_t r720 = legacyResolution(run);
  const std::size_t hsv = modeIndex(run, "hsv"), region_growing = modeIndex(run, "region_growing");
  const CellStats hsv_legacy = mergedCells(rig.legacy_cells, kAny, hsv, r720);
  const CellStats rg_legacy = mergedCells(rig.legacy_cells, kAny, region_growing, r720);
  bench::JsonLine json;
  // The earlier benchmark's keys, same meaning.
  json.number("frames", run.options.frames)
      .number("seed", static_cast<double>(run.options.seed))
      .number("frontend_p50_ms", percentile(hsv_legacy.total_ms, 0.5))
      .number("frontend_p95_ms", percentile(hsv_legacy.total_ms, 0.95))
      .number("frontend_cpu_p50_ms", percentile(hsv_legacy.cpu_ms, 0.5))
      .number("load_average_1min", bench::loadAverage())
      .number("frontend_recall", hsv_legacy.tally.legacyRecall())
      .number("frontend_precision", hsv_legacy.tally.precision())
      .number("dims_err_median_mm", percentile(hsv_legacy.quad_dim_error_mm, 0.5))
      .number("obb_dims_err_median_mm", percentile(hsv_legacy.obb_dim_error_mm, 0.5))
      .number("corner_err_median_px", percentile(hsv_legacy.corner_error_px, 0.5))
      .number("region_growing_recall", rg_legacy.tally.legacyRecall())
      .number("region_growing_precision", rg_legacy.tally.precision())
      .number("region_growing_p50_ms", percentile(rg_legacy.total_ms, 0.5));

  // Issue 10. touching_recall: the lower of hsv and the colour-free mode on
  // the touching-rows class, all resolutions; null until the rig has it.
  const ModeSpec* colour_free = headlineColourFreeMode(run.modes);
  const std::size_t colour_free_index =
      colour_free ? static_cast<std::size_t>(colour_free - run.modes.data()) : run.modes.size();
  double touching_recall = std::nan("");
  for (std::size_t c = 0; c < run.classes.size(); ++c)
    if (run.classes[c].rig_kind == "touching_rows" && run.classes[c].kind)
      for (const std::size_t m : {hsv, colour_free_index})
        if (m < run.modes.size() && run.modes[m].mode)
        {
          const double recall = mergedCells(rig.cells, c, m, kAny).tally.recall();
          if (std::isnan(recall)) continue;
          touching_recall = std::isnan(touching_recall) ? recall : std::min(touching_recall, recall);
        }
  int rig_false_complete = 0, mosd_false_complete = 0;
  for (const auto& [key, stats] : rig.cells) rig_false_complete += stats.tally.false_complete;
  // Every real-scene row counts, the colour-free modes without up included.
  for (const CellStats& stats : mosd.modes) mosd_false_complete += stats.tally.false_complete;
  for (const CellStats& stats : mosd.modes_without_up) mosd_false_complete += stats.tally.false_complete;
  json.number("touching_recall", touching_recall)
      .number("false_complete", rig.cells.empty() ? std::nan("") : rig_false_complete)
      .text("colour_free_mode", colour_free ? colour_free->name : "none")
      .number("colour_free_p50_ms_vga", colourFreeP50Ms(run, rig, "640x480"))
      .number("colour_free_p50_ms_720p", colourFreeP50Ms(run, rig, "1280x720"))
      .number("mosd_learn_recall", mosd.ran && colour_free ? mosd.modes[colour_free_index].tally.recall() : std::nan(""))
      .number("mosd_learn_false_complete", mosd.ran ? mosd_false_complete : std::nan(""));
  // Per mode, for the record.
  for (std::size_t m = 0; m < run.modes.size(); ++m)
  {
    if (!run.modes[m].mode) continue;
    const CellStats rig_mode = mergedCells(rig.cells, kAny, m, kAny);
    json.number("whole_top_recall_" + run.modes[m].name, rig_mode.tally.recall())
        .number("false_complete_" + run.modes[m].name, rig_mode.tally.false_complete)
        .number("whole_tops_type_left_open_" + run.modes[m].name, rig_mode.tally.whole_tops_type_left_open);
    if (!mosd.ran) continue;
    json.number("mosd_learn_recall_" + run.modes[m].name, mosd.modes[m].tally.recall())
        .number("mosd_learn_false_complete_" + run.modes[m].name, mosd.modes[m].tally.false_complete);
    if (run.modes[m].colour_free)
      json.number("mosd_learn_recall_" + run.modes[m].name + "_no_up", mosd.modes_without_up[m].tally.recall())
          .number("mosd_learn_false_complete_" + run.modes[m].name + "_no_up",
                  mosd.modes_without_up[m].tally.false_complete);
  }
  return json.str();
}
}  // namespace frontend_bench
}  // namespace brick_pose
