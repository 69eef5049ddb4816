// Benchmark of the perception front end (segmentation, cloud processing, ROI
// filtration) against ground truth: the synthetic D415 rig per scene class,
// mode and resolution, and the real mOSD Kinect scenes.
//
//   bench_frontend [--frames N] [--seed S] [--mosd DIR] [--mosd-catalogue FILE] [--box-catalogue FILE]
//                  [--no-mosd] [--no-rig]
//                  [--verbose] [--measured-corners] [--repeat N] [--overlay-dir DIR] [--only KINDS MODES RESOLUTIONS] [--frame N]
//
// First the earlier benchmark's block, figures unchanged in meaning: N
// frames cycling through single bricks, organised and unorganised piles and
// the normal / sunlight / low-light modes, 0.5-2 m away, 1280x720, each
// mode over the same frames. A candidate is a true positive when most of its
// pixels are the top face of one brick, its type is that brick's and no
// earlier candidate took that brick; recall counts top faces at least 60%
// visible; dimension and corner errors are measured on true positives whose
// top face is at least 95% visible.
//
// Then issue 10's table (bench_frontend/setup.h says what runs): every
// scene class the rig has (the earlier classes, then N/4 frames of each
// further class) x every segmentation mode the front end has x 1280x720,
// 848x480 and 640x480, plus the mOSD rows, scored by the eval library
// (include/brick_pose/eval): recall of whole top faces, precision, false
// complete faces and what they were, pose errors, front-end time. Prints
// the tables, then one JSON line (scripts/bench.sh collects it). With
// --overlay-dir, each mOSD scene's candidates as judged are drawn to PNGs.

#include <cstdio>

#include "bench_frontend/mosd_evaluation.h"
#include "bench_frontend/report.h"
#include "bench_frontend/rig_evaluation.h"
#include "bench_frontend/setup.h"
#include "brick_pose/catalogue/brick_catalogue.h"

using namespace brick_pose;
using namespace brick_pose::frontend_bench;

int main(int argc, char** argv)
{
  RunInfo run;
  run.options = parseOptions(argc, argv);
  run.classes = sceneClasses();
  run.modes = modes();
  run.resolutions = resolutions();
  const std::vector<FrameSpec> plan = framePlan(run.classes, run.options);
  run.planned_frames = plan.size();

  const RigResults rig =
      runRig(classCatalogues(run.classes, run.options), run.classes, run.modes, run.resolutions, plan, run.options);
  const MosdResults mosd = runMosd(run.modes, run.options);

  printLegacyBlock(run, rig);
  printTables(run, rig, mosd);
  std::printf("%s\n", jsonLine(run, rig, mosd).c_str());
  return 0;
}
