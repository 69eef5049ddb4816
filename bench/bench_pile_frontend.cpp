// The front end on one rendered pile, over and over: where its time goes
// (run it under callgrind or perf) and what it returns (a fingerprint of the
// candidates and rejections, to check that a speed-up changed nothing).
//
//   bench_pile_frontend [--repeat N] [--threads T] [--cv-threads C] [--mode M] [--up-from-truth]
//                       [name=value ...]
//
// name=value are the synthetic rig's parameters (brick_pose_simulate
// --help), e.g. scene=unorganised_pile seed=3 max_pile_bricks=12, or
// scene=touching_rows seed=14 types=red. The frame is the one the synthetic
// camera nodelet publishes first for that seed (noise seed seed * 1000), and
// the front end runs with the pipeline's defaults: mode hsv unless --mode
// (hsv, colour_free, region_growing), up from the supporting plane as in the
// demo without up_frame unless --up-from-truth.
//
// --cv-threads 1 keeps OpenCV's own loops on the calling thread: under
// callgrind (--toggle-collect=*FrontEnd::process*) the instruction counts
// then include all the work and repeat exactly.
//
// Prints per-stage wall p50, process CPU time per frame, and the
// fingerprint. The fingerprint is printed with full precision: equal text
// means equal results.

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "brick_pose/common/statistics.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/sim/rig_config.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

using namespace brick_pose;

namespace
{
struct Options
{
  int repeat = 10;
  int threads = 2;
  int cv_threads = -1;  ///< -1: OpenCV's default
  std::string mode = "hsv";
  bool up_from_truth = false;
  std::map<std::string, std::string> rig;
};

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (arg == "--repeat" && i + 1 < argc) options.repeat = std::atoi(argv[++i]);
    else if (arg == "--threads" && i + 1 < argc) options.threads = std::atoi(argv[++i]);
    else if (arg == "--cv-threads" && i + 1 < argc) options.cv_threads = std::atoi(argv[++i]);
    else if (arg == "--mode" && i + 1 < argc) options.mode = argv[++i];
    else if (arg == "--up-from-truth") options.up_from_truth = true;
    else if (arg.find('=') != std::string::npos) options.rig[arg.substr(0, arg.find('='))] = arg.substr(arg.find('=') + 1);
    else
    {
      std::fprintf(stderr, "usage: bench_pile_frontend [--repeat N] [--threads T] [--cv-threads C] [--mode M] [--up-from-truth] "
                   "[name=value ...]\n");
      std::exit(2);
    }
  }
  return options;
}

double processCpuSeconds()
{
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

/// Everything the front end returns but its timings, as text.
std::string fingerprint(const FrontEndResult& result)
{
  std::ostringstream text;
  text.precision(17);
  text << "up " << result.up.up.transpose() << " source " << static_cast<int>(result.up.source) << "\n";
  for (const BrickCandidate& c : result.candidates)
  {
    text << "candidate " << c.type_name << " complete " << c.complete << " (" << c.partial_reason << ") box "
         << c.bounding_box_px << " area " << c.area_px << " pixels " << c.pixel_indices.size() << " points "
         << (c.points ? c.points->size() : 0) << " length " << c.length_m << " width " << c.width_m << " fill "
         << c.fill_ratio << " tilt " << c.tilt_from_up_deg << " doubt '" << c.type_doubt << "'\n  normal "
         << c.normal.transpose() << " centroid " << c.plane.centroid_m.transpose() << " rms " << c.plane.rms_m << "\n  kinds";
    for (const EdgeKind kind : c.edge_kinds) text << " " << static_cast<int>(kind);
    text << "\n  corners";
    for (const auto& corner : c.corners_m) text << " " << corner.transpose();
    text << "\n";
  }
  for (const Rejection& r : result.rejections)
    text << "rejection " << r.type_name << " " << r.bounding_box_px << " " << r.area_px << " " << r.reason << "\n";
  return text.str();
}
}  // namespace

int main(int argc, char** argv)
{
  const Options options = parseOptions(argc, argv);
  if (options.cv_threads >= 0) cv::setNumThreads(options.cv_threads);
  const sim::RigConfig config = sim::rigConfigFrom(mapParamLookup(options.rig));
  const sim::SceneGenerator generator(config.catalogue, config.scene);
  const sim::Scene scene = generator.generate(config.seed);
  const sim::SyntheticFrame rendered = sim::SyntheticRig(config.camera, config.sensor).render(scene, config.seed * 1000);
  RgbdFrame frame = makeRgbdFrame(rendered.rgb, rendered.depth_mm, config.camera, FrameHeader{0, "camera"});
  if (options.up_from_truth)
    frame.up_in_camera = Eigen::Vector3d(scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ());

  FrontEndParams params;
  params.worker_threads = options.threads;
  params.mode = parseSegmentationMode(options.mode);
  const FrontEnd front_end(config.catalogue, params);

  std::vector<double> segmentation_ms, cloud_ms, roi_ms, total_ms, cpu_ms;
  std::string first;
  bool stable = true;
  for (int r = 0; r < options.repeat; ++r)
  {
    const double cpu_start = processCpuSeconds();
    const FrontEndResult result = front_end.process(frame);
    cpu_ms.push_back(1e3 * (processCpuSeconds() - cpu_start));
    segmentation_ms.push_back(result.timings.segmentation_ms);
    cloud_ms.push_back(result.timings.cloud.total());
    roi_ms.push_back(result.timings.roi_ms);
    total_ms.push_back(result.timings.total_ms);
    const std::string print = fingerprint(result);
    if (r == 0) first = print;
    else stable = stable && print == first;
  }
  std::printf("%s", first.c_str());
  std::printf("bricks in scene %zu, %dx%d, %d runs on %d threads%s\n", scene.bricks.size(), frame.width_px(),
              frame.height_px(), options.repeat, options.threads, stable ? "" : " (RESULTS DIFFER BETWEEN RUNS)");
  std::printf("p50 wall ms: segmentation %.2f  cloud %.2f  roi %.2f  total %.2f;  CPU ms per frame p50 %.2f\n",
              percentile(segmentation_ms, 0.5), percentile(cloud_ms, 0.5), percentile(roi_ms, 0.5),
              percentile(total_ms, 0.5), percentile(cpu_ms, 0.5));
  return stable ? 0 : 1;
}
