// Benchmark of the perception front end (segmentation, cloud processing, ROI
// filtration) on seeded synthetic D415 frames with ground truth.
//
//   bench_frontend [--frames N] [--seed S]
//
// Frames cycle through single bricks, organised and unorganised piles and the
// normal / sunlight / low-light modes, 0.5-2 m away. Each frame goes through
// the front end in hsv and in region_growing mode. A candidate is a true
// positive when most of its pixels are the top face of one brick instance,
// its type is that brick's and no earlier candidate took that instance.
// Recall counts top faces at least 60% visible. Dimension and corner errors
// are measured on true positives whose top face is at least 95% visible.
// Prints a table, then one JSON line.

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "brick_pose/common/statistics.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/pipeline/front_end.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

using namespace brick_pose;

namespace
{
struct Options
{
  int frames = 200;
  std::uint64_t seed = 1;
};

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if ((arg == "--frames" || arg == "--seed") && i + 1 < argc)
    {
      const std::string value = argv[++i];
      if (arg == "--frames") options.frames = std::max(1, std::atoi(value.c_str()));
      else options.seed = std::strtoull(value.c_str(), nullptr, 10);
    }
    else
    {
      std::cerr << "usage: bench_frontend [--frames N] [--seed S]\n";
      std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
    }
  }
  return options;
}

/// Accumulated results of one segmentation mode.
struct ModeStats
{
  int truths = 0;          // top faces >= 60% visible
  int truths_found = 0;
  int candidates = 0;
  int true_positives = 0;
  std::vector<double> quad_dim_error_mm;
  std::vector<double> obb_dim_error_mm;
  std::vector<double> corner_error_px;
  std::vector<double> total_ms, segmentation_ms, cloud_ms, roi_ms;
  std::vector<double> cpu_ms;  // process CPU time of the same calls (all threads)
  std::map<std::string, int> false_positive_reasons;
  std::map<std::string, int> miss_reasons;

  double recall() const { return truths ? static_cast<double>(truths_found) / truths : 1.0; }
  double precision() const { return candidates ? static_cast<double>(true_positives) / candidates : 1.0; }
};

/// Instance (1-based, 0 none) whose top face covers most of the candidate's pixels.
int topFaceInstance(const BrickCandidate& candidate, const sim::SyntheticFrame& frame, double& top_share)
{
  std::map<int, int> votes;
  const auto* instances = frame.instance_labels.ptr<std::uint16_t>(0);
  const auto* faces = frame.face_labels.ptr<std::uint8_t>(0);
  for (const int pixel : candidate.pixel_indices)
    if (faces[pixel] == static_cast<std::uint8_t>(sim::CuboidFace::kTop)) ++votes[instances[pixel]];
  int best = 0, best_votes = 0;
  for (const auto& [instance, count] : votes)
    if (count > best_votes) { best = instance; best_votes = count; }
  top_share = candidate.pixel_indices.empty() ? 0.0 : static_cast<double>(best_votes) / candidate.pixel_indices.size();
  return best;
}

/// Mean over corners of the distance to the truth corners, for the best
/// cyclic correspondence (either direction).
std::vector<double> cornerErrorsPx(const BrickCandidate& candidate, const std::array<Eigen::Vector2d, 4>& truth)
{
  std::vector<double> best;
  double best_sum = 1e18;
  for (int direction : {1, -1})
    for (int shift = 0; shift < 4; ++shift)
    {
      std::vector<double> errors;
      double sum = 0.0;
      for (int k = 0; k < 4; ++k)
      {
        const int t = ((shift + direction * k) % 4 + 4) % 4;
        errors.push_back((candidate.corners_px[k] - truth[t]).norm());
        sum += errors.back();
      }
      if (sum < best_sum) { best_sum = sum; best = errors; }
    }
  return best;
}

double loadAverage()
{
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

double processCpuMs()
{
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return 1e3 * static_cast<double>(now.tv_sec) + 1e-6 * static_cast<double>(now.tv_nsec);
}

/// Runs the front end on one frame, recording its CPU time too: other
/// processes sharing the 2 cores inflate the wall time, not the CPU time.
FrontEndResult timedProcess(const FrontEnd& front_end, const RgbdFrame& frame, ModeStats& stats)
{
  const double cpu_start = processCpuMs();
  FrontEndResult result = front_end.process(frame);
  stats.cpu_ms.push_back(processCpuMs() - cpu_start);
  return result;
}

void evaluate(const FrontEndResult& result, const sim::SyntheticFrame& frame, const PinholeCamera& camera,
              ModeStats& stats)
{
  stats.total_ms.push_back(result.timings.total_ms);
  stats.segmentation_ms.push_back(result.timings.segmentation_ms);
  stats.cloud_ms.push_back(result.timings.cloud.total());
  stats.roi_ms.push_back(result.timings.roi_ms);

  std::vector<bool> taken(frame.truth.size() + 1, false);
  for (const BrickCandidate& candidate : result.candidates)
  {
    ++stats.candidates;
    double top_share = 0.0;
    const int instance = topFaceInstance(candidate, frame, top_share);
    const sim::BrickTruth* truth = instance > 0 ? &frame.truth[instance - 1] : nullptr;
    std::string failure;
    if (!truth || top_share < 0.5) failure = "not mostly one top face";
    else if (truth->type != candidate.type_name) failure = "wrong type (" + candidate.type_name + " for " + truth->type + ")";
    else if (taken[instance]) failure = "duplicate of an instance";
    if (!failure.empty())
    {
      if (std::getenv("BENCH_VERBOSE"))
        std::fprintf(stderr, "false positive %s %.3f x %.3f m, %d px, complete %d, fill %.2f: %s\n",
                     candidate.type_name.c_str(), candidate.length_m, candidate.width_m, candidate.area_px,
                     candidate.complete ? 1 : 0, candidate.fill_ratio, failure.c_str());
      ++stats.false_positive_reasons[failure];
      continue;
    }
    taken[instance] = true;
    ++stats.true_positives;
    if (truth->visible_fraction < 0.95) continue;
    const Eigen::Vector3d dims = truth->dimensions_m;
    stats.quad_dim_error_mm.push_back(1000.0 * std::abs(candidate.length_m - dims.x()));
    stats.quad_dim_error_mm.push_back(1000.0 * std::abs(candidate.width_m - dims.y()));
    stats.obb_dim_error_mm.push_back(1000.0 * std::abs(candidate.obb.extents_m.x() - dims.x()));
    stats.obb_dim_error_mm.push_back(1000.0 * std::abs(candidate.obb.extents_m.y() - dims.y()));
    std::array<Eigen::Vector2d, 4> corners_px;
    const auto corners_m = sim::topFaceCornersInCamera(*truth);
    for (int k = 0; k < 4; ++k) corners_px[k] = camera.project(corners_m[k]);
    for (const double e : cornerErrorsPx(candidate, corners_px)) stats.corner_error_px.push_back(e);
  }

  for (const sim::BrickTruth& truth : frame.truth)
  {
    if (truth.visible_fraction < 0.6) continue;
    ++stats.truths;
    if (taken[truth.instance_id]) { ++stats.truths_found; continue; }
    // Why was it missed? The rejection whose box holds most of the face.
    std::string reason = "no segment";
    for (const Rejection& rejection : result.rejections)
    {
      int inside = 0;
      for (int v = rejection.bounding_box_px.y; v < rejection.bounding_box_px.br().y; v += 2)
        for (int u = rejection.bounding_box_px.x; u < rejection.bounding_box_px.br().x; u += 2)
          if (frame.instance_labels.at<std::uint16_t>(v, u) == truth.instance_id &&
              frame.face_labels.at<std::uint8_t>(v, u) == static_cast<std::uint8_t>(sim::CuboidFace::kTop))
            ++inside;
      if (inside * 4 > truth.visible_top_pixels / 3)
      {
        reason = rejection.reason.substr(0, rejection.reason.find_first_of("0123456789"));
        if (std::getenv("BENCH_VERBOSE"))
          std::fprintf(stderr, "miss %s vis %.2f z %.2f: %s\n", truth.type.c_str(), truth.visible_fraction,
                       truth.camera_T_brick.translation().z(), rejection.reason.c_str());
        break;
      }
    }
    ++stats.miss_reasons[reason];
  }
}

void printMode(const std::string& name, const ModeStats& stats)
{
  const double p50 = percentile(stats.total_ms, 0.5);
  std::printf("\n== %s ==\n", name.c_str());
  std::printf("  recall     %6.4f  (%d / %d top faces >= 60%% visible)\n", stats.recall(), stats.truths_found, stats.truths);
  std::printf("  precision  %6.4f  (%d / %d candidates)\n", stats.precision(), stats.true_positives, stats.candidates);
  std::printf("  dims error median  quad %.2f mm   obb %.2f mm   (n = %zu)\n", percentile(stats.quad_dim_error_mm, 0.5),
              percentile(stats.obb_dim_error_mm, 0.5), stats.quad_dim_error_mm.size());
  std::printf("  corner error px    median %.3f  p90 %.3f  (n = %zu)\n", percentile(stats.corner_error_px, 0.5),
              percentile(stats.corner_error_px, 0.9), stats.corner_error_px.size());
  std::printf("  time ms per frame  p50 %.2f  p95 %.2f  mean %.2f  (wall)\n", p50, percentile(stats.total_ms, 0.95),
              mean(stats.total_ms));
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
}  // namespace

int main(int argc, char** argv)
{
  const Options options = parseOptions(argc, argv);
  const BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  const PinholeCamera camera = PinholeCamera::d415Color1280x720();

  const std::vector<sim::SceneKind> kinds = {sim::SceneKind::kSingle, sim::SceneKind::kOrganisedPile,
                                             sim::SceneKind::kUnorganisedPile};
  const std::vector<sim::Lighting> lightings = {sim::Lighting::kNormal, sim::Lighting::kSunlight, sim::Lighting::kLowLight};
  std::vector<sim::SceneGenerator> generators;
  for (const sim::SceneKind kind : kinds)
  {
    sim::SceneParams params;
    params.kind = kind;
    params.min_distance_m = 0.5;
    params.max_distance_m = 2.0;
    generators.emplace_back(catalogue, params);
  }

  FrontEndParams hsv_params;
  hsv_params.mode = SegmentationMode::kHsv;
  const FrontEnd hsv_front_end(catalogue, hsv_params);

  ModeStats hsv_stats, rg_stats;
  std::vector<double> frame_build_ms;
  // Frame i of the sequence: scene, rendering and ground truth.
  struct BenchFrame
  {
    sim::Scene scene;
    sim::SyntheticFrame synthetic;
  };
  auto render = [&](int i) {
    const std::uint64_t frame_seed = options.seed * 1000003ULL + static_cast<std::uint64_t>(i);
    // Two singles in four frames: single bricks are the common case.
    const int kind_index = i % 4 == 3 ? 2 : (i % 4 == 2 ? 1 : 0);
    BenchFrame frame;
    frame.scene = generators[kind_index].generate(frame_seed);
    sim::SensorModel sensor;
    sensor.lighting = lightings[(i / 4) % 3];
    frame.synthetic = sim::SyntheticRig(camera, sensor).render(frame.scene, frame_seed);
    return frame;
  };
  auto toRgbd = [&](const BenchFrame& bench_frame, int i) {
    FrameHeader header;
    header.stamp_ns = static_cast<std::int64_t>(i) * 33333333;
    header.frame_id = "camera_color_optical_frame";
    return makeRgbdFrame(bench_frame.synthetic.rgb, bench_frame.synthetic.depth_mm, camera, header);
  };

  // The modes run in separate passes over the same (re-rendered, bit-identical)
  // frames, so that region growing's large allocations do not disturb the
  // hsv timings.
  for (int i = 0; i < options.frames; ++i)
  {
    const BenchFrame bench_frame = render(i);
    const auto build_start = std::chrono::steady_clock::now();
    const RgbdFrame frame = toRgbd(bench_frame, i);
    frame_build_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - build_start).count());
    evaluate(timedProcess(hsv_front_end, frame, hsv_stats), bench_frame.synthetic, camera, hsv_stats);
  }
  for (int i = 0; i < options.frames; ++i)
  {
    const BenchFrame bench_frame = render(i);
    // Colour-free mode: gravity is known on a robot (tf); without it the long
    // side faces of a brick have the size of a top face.
    FrontEndParams rg_params;
    rg_params.mode = SegmentationMode::kRegionGrowing;
    rg_params.roi.up_direction = bench_frame.scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
    const FrontEnd rg_front_end(catalogue, rg_params);
    evaluate(timedProcess(rg_front_end, toRgbd(bench_frame, i), rg_stats), bench_frame.synthetic, camera, rg_stats);
  }

  std::printf("bench_frontend: %d frames, seed %llu, 1280x720, 0.5-2 m, singles/organised/unorganised piles, "
              "normal/sunlight/low_light\n",
              options.frames, static_cast<unsigned long long>(options.seed));
  std::printf("frame build (makeRgbdFrame, 16UC1 -> metres): p50 %.2f ms (not part of the front-end time)\n",
              percentile(frame_build_ms, 0.5));
  std::printf("load average (1 min) at the end: %.2f on %d cores: wall times include waiting for other processes\n",
              loadAverage(), 2);
  printMode("hsv", hsv_stats);
  printMode("region_growing", rg_stats);

  std::ostringstream json;
  json.precision(6);
  json << "{\"frames\": " << options.frames << ", \"seed\": " << options.seed
       << ", \"frontend_p50_ms\": " << percentile(hsv_stats.total_ms, 0.5)
       << ", \"frontend_p95_ms\": " << percentile(hsv_stats.total_ms, 0.95)
       << ", \"frontend_cpu_p50_ms\": " << percentile(hsv_stats.cpu_ms, 0.5)
       << ", \"load_average_1min\": " << loadAverage()
       << ", \"frontend_recall\": " << hsv_stats.recall() << ", \"frontend_precision\": " << hsv_stats.precision()
       << ", \"dims_err_median_mm\": " << percentile(hsv_stats.quad_dim_error_mm, 0.5)
       << ", \"obb_dims_err_median_mm\": " << percentile(hsv_stats.obb_dim_error_mm, 0.5)
       << ", \"corner_err_median_px\": " << percentile(hsv_stats.corner_error_px, 0.5)
       << ", \"region_growing_recall\": " << rg_stats.recall()
       << ", \"region_growing_precision\": " << rg_stats.precision()
       << ", \"region_growing_p50_ms\": " << percentile(rg_stats.total_ms, 0.5) << "}";
  std::printf("%s\n", json.str().c_str());
  return 0;
}
