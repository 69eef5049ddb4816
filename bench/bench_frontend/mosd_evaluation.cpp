#include "bench_frontend/mosd_evaluation.h"

#include <opencv2/imgcodecs.hpp>

#include "brick_pose/common/errors.h"
#include "brick_pose/eval/match_overlay.h"
#include "brick_pose/eval/mosd_catalogue.h"
#include "brick_pose/eval/mosd_scene.h"
#include "brick_pose/eval/mosd_truth.h"
#include "common/run_environment.h"

namespace brick_pose
{
namespace frontend_bench
{
namespace
{
/// The scene's table, measured from its labels, as (n, d) with n . p + d = 0
/// and n up (toward the camera); zero without a table.
Eigen::Vector4d tablePlane(const eval::MosdTruth& truth)
{
  if (!truth.has_table) return Eigen::Vector4d::Zero();
  const Eigen::Vector3d& normal = truth.table.normal;
  Eigen::Vector4d plane;
  plane << normal, -normal.dot(truth.table.centroid_m);
  return plane;
}
}  // namespace

MosdResults runMosd(const std::vector<ModeSpec>& modes, const Options& options)
{
  MosdResults results;
  results.modes.resize(modes.size());
  results.modes_without_up.resize(modes.size());
  if (options.skip_mosd)
  {
    results.skipped_reason = "--no-mosd";
    return results;
  }
  const std::string directory =
      options.mosd_dir.empty() ? eval::mosdLearnDirectory(bench::sourceDirectory()) : options.mosd_dir;
  results.catalogue_path =
      options.mosd_catalogue.empty() ? eval::mosdCataloguePath(bench::sourceDirectory()) : options.mosd_catalogue;
  const std::vector<std::string> names = eval::mosdSceneNames(directory);
  if (names.empty())
  {
    results.skipped_reason = "no scenes in " + directory;
    return results;
  }
  BrickCatalogue catalogue;
  try
  {
    catalogue = BrickCatalogue::fromYamlFile(results.catalogue_path);
  }
  catch (const ConfigError& error)
  {
    results.skipped_reason = error.what();
    return results;
  }
  results.catalogue_types = catalogue.types().size();

  // Truth first (it does not depend on the mode), then mode by mode.
  std::vector<eval::MosdScene> scenes;
  std::vector<eval::MosdTruth> truths;
  for (const std::string& name : names)
  {
    scenes.push_back(eval::loadMosdScene(directory, name));
    truths.push_back(eval::extractMosdTruth(scenes.back()));
  }
  const eval::MatchParams match_params;
  for (std::size_t m = 0; m < modes.size(); ++m)
  {
    if (!modes[m].mode) continue;
    for (const bool with_up : {true, false})
    {
      if (!with_up && !modes[m].colour_free) continue;
      for (std::size_t s = 0; s < scenes.size(); ++s)
      {
        // With up given, the table is given too, as a robot's tf would
        // give the plane the boxes stand on (support_frame).
        const FrontEnd front_end(catalogue, with_up ? frontEndParamsFor(modes[m], truths[s].up, tablePlane(truths[s]),
                                                                      options.measured_corners)
                                                    : frontEndParamsFor(modes[m], Eigen::Vector3d::Zero(),
                                                                      Eigen::Vector4d::Zero(),
                                                                      options.measured_corners));
        const double cpu_start = bench::processCpuMs();
        const FrontEndResult result = front_end.process(scenes[s].frame);
        const double cpu_ms = bench::processCpuMs() - cpu_start;
        const std::string row = modes[m].name + (with_up ? "" : "_no_up");
        recordFrame(result, cpu_ms, truths[s].scene, scenes[s].frame.camera, match_params, options.verbose,
                    "mosd " + scenes[s].name + " " + row, with_up ? results.modes[m] : results.modes_without_up[m]);
        if (!options.overlay_dir.empty())
        {
          const eval::FrameMatch match =
              eval::matchCandidates(result.candidates, truths[s].scene, scenes[s].frame.camera, match_params);
          cv::imwrite(options.overlay_dir + "/" + scenes[s].name + "_" + row + ".png",
                      eval::drawMatchOverlay(scenes[s].frame.rgb, truths[s].scene, result.candidates, match,
                                             scenes[s].frame.camera));
        }
      }
    }
  }
  results.ran = true;
  results.scenes = static_cast<int>(scenes.size());
  return results;
}
}  // namespace frontend_bench
}  // namespace brick_pose
