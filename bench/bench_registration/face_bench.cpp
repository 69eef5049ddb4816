#include "bench_registration/face_bench.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "bench_registration/face_cases.h"
#include "bench_registration/outcomes.h"
#include "bench_registration/pcl_sweep.h"
#include "brick_pose/baselines/pcl_baselines.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/registration/model_cloud.h"
#include "brick_pose/registration/super4pcs.h"

namespace bench_registration
{
using namespace brick_pose;
using namespace brick_pose::registration;

namespace
{
/// Where Super4PCS spends its CPU time, overall and by brick type.
void printPhaseProfile(const MethodStats& ours, const std::map<std::string, MethodStats>& ours_by_type)
{
  std::printf("\nSuper4PCS CPU time by phase, median / p95 (ms):\n\n| faces | setup | search | refine | total |\n"
              "|---|---:|---:|---:|---:|\n");
  auto row = [](const std::string& label, const MethodStats& stats) {
    const auto setup = quantiles(stats, &Outcome::setup_cpu_ms);
    const auto search = quantiles(stats, &Outcome::search_cpu_ms);
    const auto refine = quantiles(stats, &Outcome::refine_cpu_ms);
    const auto total = quantiles(stats, &Outcome::cpu_ms);
    std::printf("| %s | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f | %.1f / %.1f |\n", label.c_str(), setup.first,
                setup.second, search.first, search.second, refine.first, refine.second, total.first, total.second);
  };
  row("all", ours);
  for (const auto& [name, stats] : ours_by_type)
    row(name, stats);
}
}  // namespace

std::string runFaceBench(const Options& options)
{
  RigFaceSource faces(options.seed, options.min_visible_fraction);
  std::map<std::string, PointSet> models;
  MethodStats ours{"Super4PCS (ours)", "s4pcs", {}};
  MethodStats fpcs{"PCL FPCS", "pcl_fpcs", {}};
  MethodStats kfpcs{"PCL KFPCS", "pcl_kfpcs", {}};
  MethodStats icp{"PCL ICP from identity", "pcl_icp", {}};
  std::map<std::string, MethodStats> ours_by_type;
  int skipped = 0;
  int input_errors = 0;
  std::vector<double> segment_sizes;
  std::vector<FaceSample> sweep_faces;  // the first sweep_frames faces

  for (int frame = 0; frame < options.frames; ++frame)
  {
    const FaceSample sample = faces.next(skipped);
    if (!options.only_ours && frame < options.sweep_frames)
      sweep_faces.push_back(sample);
    if (options.verbose)
    {
      Eigen::Vector3d lower = Eigen::Vector3d::Constant(1e9), upper = -lower;
      std::vector<double> xs;
      for (const Eigen::Vector3d& p : sample.segment.points)
      {
        const Eigen::Vector3d b = sample.camera_T_brick.inverse() * p;
        lower = lower.cwiseMin(b);
        upper = upper.cwiseMax(b);
        xs.push_back(b.x());
      }
      std::cerr << "face " << frame << " " << sample.type.name << " at " << sample.distance_m << " m, "
                << sample.segment.size() << " points, brick-frame x [" << 1e3 * lower.x() << ", " << 1e3 * upper.x()
                << "] y [" << 1e3 * lower.y() << ", " << 1e3 * upper.y() << "] z [" << 1e3 * lower.z() << ", "
                << 1e3 * upper.z() << "] x1% " << 1e3 * percentile(xs, 0.01) << " x99% " << 1e3 * percentile(xs, 0.99)
                << "\n";
    }
    segment_sizes.push_back(static_cast<double>(sample.segment.size()));
    if (!models.count(sample.type.name))
      models[sample.type.name] = buildBrickModelCloud(sample.type);
    const PointSet& model = models[sample.type.name];

    Super4PCSParams params;
    params.seed = options.seed + frame;
    if (options.no_refine)
    {
      params.refine_iterations = 0;
      params.fine_refine_iterations = 0;
    }
    PclFpcsParams pcl_params;
    pcl_params.overlap = params.overlap;
    pcl_params.delta_m = params.delta_m;
    pcl_params.sample_size = params.sample_size;
    pcl_params.max_time_s = options.pcl_time_s;
    // ICP from the identity: the model sits at the camera origin, the face
    // 0.5-2 m away; the correspondence radius has to reach that far.
    IcpParams icp_params;
    icp_params.max_correspondence_distance_m = 2.5;
    icp_params.max_iterations = 50;
    icp_params.transformation_epsilon_m2 = 1e-8;
    icp_params.relative_fitness_epsilon = 0.0;  // PCL's fitness criterion off, as in earlier runs

    const std::vector<std::pair<MethodStats*, std::function<RegistrationResult()>>> runs{
        {&ours, [&] { return Super4PCS(params).align(model, sample.segment); }},
        {&fpcs, [&] { return alignPclFpcs(model, sample.segment, pcl_params); }},
        {&kfpcs, [&] { return alignPclKfpcs(model, sample.segment, pcl_params); }},
        {&icp, [&] { return alignPclIcp(model, sample.segment, icp_params); }},
    };
    for (const auto& [stats, run] : runs)
    {
      if (options.only_ours && stats != &ours)
        continue;
      try
      {
        const double cpu_start_s = threadCpuSeconds();
        const RegistrationResult result = run();
        const double cpu_s = threadCpuSeconds() - cpu_start_s;
        Outcome outcome = judgeFace(result, sample.camera_T_brick);
        outcome.cpu_ms = 1e3 * cpu_s;
        outcome.setup_cpu_ms = std::max(0.0, outcome.cpu_ms - outcome.search_cpu_ms - outcome.refine_cpu_ms);
        if (options.verbose)
          std::cerr << "  offset in brick frame (mm) "
                    << (1e3 * (sample.camera_T_brick.inverse() * result.source_to_target.translation())).transpose()
                    << "  " << stats->name << ": " << outcome.time_ms << " ms, " << outcome.rotation_deg << " deg, "
                    << outcome.translation_mm << " mm, LCP " << result.lcp_score << ", " << result.bases_tried
                    << " bases, " << result.reason << "\n";
        stats->outcomes.push_back(outcome);
        if (stats == &ours)
        {
          MethodStats& by_type = ours_by_type[sample.type.name];
          by_type.name = sample.type.name;
          by_type.outcomes.push_back(outcome);
        }
      }
      catch (const InputError& e)
      {
        ++input_errors;
        std::cerr << "frame " << frame << " " << stats->name << ": " << e.what() << "\n";
        stats->outcomes.push_back(Outcome{});  // counted as a failure
      }
    }
    if ((frame + 1) % 20 == 0)
      std::cerr << "bench_registration: " << (frame + 1) << "/" << options.frames << " faces\n";
  }

  std::printf("\n## Registration of segmented brick top faces (synthetic D415, 0.5-2 m)\n\n");
  std::printf("%d faces (%d frames skipped: top face < %.0f%% visible or < %d points), segment size median %.0f "
              "points (min %.0f, max %.0f). Success: rotation < %.0f deg and translation < %.0f mm modulo the "
              "face symmetry.\n\n",
              options.frames, skipped, 100.0 * options.min_visible_fraction, kMinSegmentPoints, percentile(segment_sizes, 0.5),
              percentile(segment_sizes, 0.0), percentile(segment_sizes, 1.0), kSuccessRotationDeg,
              1e3 * kSuccessTranslationM);
  std::printf("| method | median ms | p95 ms | median CPU ms | p95 CPU ms | success | median rot. err. (deg) | "
              "median transl. err. (mm) |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|\n");
  std::map<std::string, Summary> summaries;
  for (const MethodStats* stats : {&ours, &fpcs, &kfpcs, &icp})
  {
    const Summary s = summarise(*stats);
    summaries[stats->json_key] = s;
    std::printf("| %s | %.1f | %.1f | %.1f | %.1f | %.1f%% | %.2f | %.1f |\n", stats->name.c_str(), s.median_ms,
                s.p95_ms, s.median_cpu_ms, s.p95_cpu_ms, 100.0 * s.success, s.median_rotation_deg,
                s.median_translation_mm);
  }
  std::printf("\nSuper4PCS by brick type:\n\n| type | faces | median ms | p95 ms | median CPU ms | success | "
              "median rot. (deg) | median transl. (mm) |\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [name, stats] : ours_by_type)
  {
    const Summary s = summarise(stats);
    std::printf("| %s | %zu | %.1f | %.1f | %.1f | %.1f%% | %.2f | %.1f |\n", name.c_str(), stats.outcomes.size(),
                s.median_ms, s.p95_ms, s.median_cpu_ms, 100.0 * s.success, s.median_rotation_deg,
                s.median_translation_mm);
  }
  printPhaseProfile(ours, ours_by_type);
  if (input_errors > 0)
    std::printf("\n%d registrations rejected their input (counted as failures).\n", input_errors);
  // The fair comparison: PCL at the setting closest to our success, on the
  // sweep faces, against ours on the same faces.
  std::vector<SweepRow> fpcs_sweep;
  std::vector<SweepRow> kfpcs_sweep;
  MethodStats ours_on_sweep{"Super4PCS (ours)", "s4pcs", {}};
  if (!sweep_faces.empty())
  {
    ours_on_sweep.outcomes.assign(ours.outcomes.begin(), ours.outcomes.begin() + sweep_faces.size());
    PclFpcsParams shared;
    const std::vector<SweepSetting> settings = sweepSettings(shared, options.sweep_time_s);
    fpcs_sweep = runSweep("PCL FPCS", alignPclFpcs, settings, sweep_faces, models);
    kfpcs_sweep = runSweep("PCL KFPCS", alignPclKfpcs, settings, sweep_faces, models);
  }
  const Summary ours_sweep = summarise(ours_on_sweep);
  std::ostringstream sweep_json;
  sweep_json.setf(std::ios::fixed);
  sweep_json.precision(4);
  if (!sweep_faces.empty())
  {
    std::printf("\nPCL 4PCS at other settings, on the first %zu faces (PCL calls capped at %d s). Ours on the same "
                "faces: %.1f%% success, median %.1f ms wall / %.1f ms CPU.\n\n",
                sweep_faces.size(), options.sweep_time_s, 100.0 * ours_sweep.success, ours_sweep.median_ms,
                ours_sweep.median_cpu_ms);
    std::printf("| method | setting | median ms | p95 ms | median CPU ms | success | median rot. err. (deg) | "
                "median transl. err. (mm) |\n|---|---|---:|---:|---:|---:|---:|---:|\n");
    for (const std::vector<SweepRow>* rows : {&fpcs_sweep, &kfpcs_sweep})
      for (const SweepRow& row : *rows)
      {
        const Summary r = summarise(row.stats);
        std::printf("| %s | %s | %.1f | %.1f | %.1f | %.1f%% | %.2f | %.1f |\n", row.method.c_str(),
                    row.label.c_str(), r.median_ms, r.p95_ms, r.median_cpu_ms, 100.0 * r.success,
                    r.median_rotation_deg, r.median_translation_mm);
      }
    std::printf("\n");
    sweep_json << ", \"sweep_frames\": " << sweep_faces.size() << ", \"s4pcs_sweep_success\": " << ours_sweep.success
               << ", \"s4pcs_sweep_median_ms\": " << ours_sweep.median_ms
               << ", \"s4pcs_sweep_median_cpu_ms\": " << ours_sweep.median_cpu_ms;
    for (const auto& [rows, key] : {std::make_pair(&fpcs_sweep, "pcl_fpcs"), std::make_pair(&kfpcs_sweep, "pcl_kfpcs")})
    {
      bool reaches = false;
      const SweepRow* matched = matchedRow(*rows, ours_sweep.success, reaches);
      const Summary m = summarise(matched->stats);
      if (reaches)
        std::printf("%s matches our success (%.1f%% >= %.1f%%) at \"%s\", fastest such setting: median %.1f ms "
                    "wall / %.1f ms CPU, %.1fx our median wall time.\n",
                    matched->method.c_str(), 100.0 * m.success, 100.0 * ours_sweep.success, matched->label.c_str(),
                    m.median_ms, m.median_cpu_ms, m.median_ms / ours_sweep.median_ms);
      else
        std::printf("%s does not reach our success at any setting tried: at most %.1f%% (ours %.1f%%), at \"%s\", "
                    "median %.1f ms wall / %.1f ms CPU. Its matched_* figures below are that closest setting, at "
                    "lower success.\n",
                    matched->method.c_str(), 100.0 * m.success, 100.0 * ours_sweep.success, matched->label.c_str(),
                    m.median_ms, m.median_cpu_ms);
      sweep_json << ", \"" << key << "_matched_setting\": \"" << matched->label << "\", \"" << key
                 << "_matched_median_ms\": " << m.median_ms << ", \"" << key
                 << "_matched_median_cpu_ms\": " << m.median_cpu_ms << ", \"" << key
                 << "_matched_success\": " << m.success << ", \"" << key
                 << "_matched_reaches_ours\": " << (reaches ? "true" : "false") << ", \"speedup_vs_" << key
                 << "_matched\": " << m.median_ms / ours_sweep.median_ms << ", \"speedup_vs_" << key
                 << "_matched_cpu\": " << m.median_cpu_ms / ours_sweep.median_cpu_ms;
    }
  }

  const Summary& s = summaries["s4pcs"];
  static char buffer[8192];
  const auto search_cpu = quantiles(ours, &Outcome::search_cpu_ms);
  const auto refine_cpu = quantiles(ours, &Outcome::refine_cpu_ms);
  std::snprintf(buffer, sizeof(buffer), "\"frames\": %d, \"s4pcs_median_ms\": %.3f, \"s4pcs_p95_ms\": %.3f, \"s4pcs_median_cpu_ms\": %.3f, "
              "\"s4pcs_p95_cpu_ms\": %.3f, \"s4pcs_success\": %.4f, "
              "\"s4pcs_median_rot_deg\": %.3f, \"s4pcs_median_trans_mm\": %.3f, "
              "\"s4pcs_median_search_cpu_ms\": %.3f, \"s4pcs_median_refine_cpu_ms\": %.3f, "
              "\"pcl_fpcs_median_ms\": %.3f, \"pcl_fpcs_p95_ms\": %.3f, \"pcl_fpcs_median_cpu_ms\": %.3f, "
              "\"pcl_fpcs_success\": %.4f, "
              "\"pcl_kfpcs_median_ms\": %.3f, \"pcl_kfpcs_p95_ms\": %.3f, \"pcl_kfpcs_success\": %.4f, "
              "\"pcl_icp_median_ms\": %.3f, \"pcl_icp_success\": %.4f, \"speedup_vs_pcl_fpcs\": %.2f%s",
              options.frames, s.median_ms, s.p95_ms, s.median_cpu_ms, s.p95_cpu_ms, s.success, s.median_rotation_deg,
              s.median_translation_mm, search_cpu.first, refine_cpu.first,
              summaries["pcl_fpcs"].median_ms, summaries["pcl_fpcs"].p95_ms, summaries["pcl_fpcs"].median_cpu_ms,
              summaries["pcl_fpcs"].success,
              summaries["pcl_kfpcs"].median_ms, summaries["pcl_kfpcs"].p95_ms, summaries["pcl_kfpcs"].success,
              summaries["pcl_icp"].median_ms, summaries["pcl_icp"].success,
              summaries["pcl_fpcs"].median_ms / s.median_ms, sweep_json.str().c_str());
  return buffer;
}
}  // namespace bench_registration
