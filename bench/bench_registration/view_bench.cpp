#include "bench_registration/view_bench.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include "bench_registration/outcomes.h"
#include "bench_registration/view_cases.h"
#include "brick_pose/baselines/pcl_baselines.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/statistics.h"
#include "brick_pose/registration/brick_symmetry.h"
#include "brick_pose/registration/model_cloud.h"
#include "brick_pose/registration/super4pcs.h"

namespace bench_registration
{
using namespace brick_pose;
using namespace brick_pose::registration;

namespace
{
constexpr double kModelSpacingM = 0.01;

/// FNV-1a over the bytes of every result that matters: equal digests for two
/// runs mean identical poses, scores and claims.
class Digest
{
public:
  void add(const void* data, std::size_t size)
  {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
      hash_ = (hash_ ^ bytes[i]) * 1099511628211ull;
  }
  void add(const RegistrationResult& result)
  {
    add(result.source_to_target.matrix().data(), 16 * sizeof(double));
    add(&result.confidence, sizeof(double));
    add(&result.success, sizeof(bool));
    add(&result.bases_tried, sizeof(int));
    add(&result.candidates_verified, sizeof(int));
  }
  std::uint64_t value() const { return hash_; }

private:
  std::uint64_t hash_ = 1469598103934665603ull;
};

Super4PCSParams viewParams(std::uint64_t seed, bool no_refine)
{
  Super4PCSParams params;
  params.seed = seed;
  params.view.mode = ViewMode::kOn;
  // The work budget (bases, candidates) bounds the search; the wall clock is
  // only a safety net here, far above what the work takes.
  params.max_time_s = 5.0;
  if (no_refine)
  {
    params.refine_iterations = 0;
    params.fine_refine_iterations = 0;
  }
  return params;
}

/// PCL's 4PCS registers the scan (all of which lies on the model) onto the
/// model, the direction our search takes too; the result is inverted.
RegistrationResult pclOnView(RegistrationResult (*align)(const PointSet&, const PointSet&, const PclFpcsParams&),
                             const PointSet& model, const PointSet& scan, int time_s)
{
  PclFpcsParams params;
  params.overlap = 0.9;
  params.max_time_s = time_s;
  RegistrationResult result = align(scan, model, params);
  result.source_to_target = result.source_to_target.inverse();
  return result;
}

void printRow(const std::string& label, const MethodStats& stats)
{
  const Summary s = summarise(stats);
  std::printf("| %s | %zu | %.1f%% | %d | %.1f | %.1f | %.1f | %.1f | %.2f | %.1f |\n", label.c_str(),
              stats.outcomes.size(), 100.0 * s.success, s.false_successes, s.median_cpu_ms, s.p95_cpu_ms, s.median_ms,
              s.p95_ms, s.median_rotation_deg, s.median_translation_mm);
}

void printHeader(const char* first_column)
{
  std::printf("| %s | cases | success | false success | median CPU ms | p95 CPU ms | median ms | p95 ms | "
              "median rot. (deg) | median transl. (mm) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n",
              first_column);
}
}  // namespace

std::string runViewBench(const Options& options)
{
  const std::vector<BrickType> types = viewCaseTypes(BrickCatalogue::mbzirc2020());
  const RigViewSource source(options.seed, types);
  std::map<std::string, PointSet> models;
  MethodStats ours{"Super4PCS whole view (ours)", "s4pcs_views", {}};
  MethodStats fpcs{"PCL FPCS", "pcl_fpcs_views", {}};
  MethodStats kfpcs{"PCL KFPCS", "pcl_kfpcs_views", {}};
  std::map<std::string, MethodStats> by_type;
  std::map<std::string, MethodStats> by_layout;
  std::vector<double> scan_sizes;
  std::vector<std::string> unsure_right;
  std::vector<std::string> wrong;
  Digest digest;
  int redraws = 0;

  for (int index = options.first_view; index < options.first_view + options.views; ++index)
  {
    const ViewCase view = source.make(index, redraws);
    scan_sizes.push_back(static_cast<double>(view.scan.size()));
    if (!models.count(view.type.name))
      models[view.type.name] = buildCuboidSurfaceCloud(view.type, kModelSpacingM);
    const PointSet& model = models[view.type.name];
    const std::vector<Eigen::Isometry3d> symmetries = cuboidSymmetries(view.type.dimensions_m());
    const Super4PCSParams params = viewParams(options.seed + index, options.no_refine);

    const std::vector<std::pair<MethodStats*, std::function<RegistrationResult()>>> runs{
        {&ours, [&] { return Super4PCS(params).align(model, view.scan); }},
        {&fpcs, [&] { return pclOnView(alignPclFpcs, model, view.scan, options.pcl_time_s); }},
        {&kfpcs, [&] { return pclOnView(alignPclKfpcs, model, view.scan, options.pcl_time_s); }},
    };
    for (const auto& [stats, run] : runs)
    {
      if (options.only_ours && stats != &ours)
        continue;
      Outcome outcome;
      RegistrationResult result;
      try
      {
        const double cpu_start_s = threadCpuSeconds();
        result = run();
        const double cpu_s = threadCpuSeconds() - cpu_start_s;
        const PoseError error = poseErrorModuloSymmetries(result.source_to_target, view.camera_T_brick, symmetries);
        outcome = outcomeOf(result, error.rotation_deg, error.translation_mm());
        outcome.cpu_ms = 1e3 * cpu_s;
      }
      catch (const InputError& e)
      {
        std::cerr << "view " << index << " " << stats->name << ": " << e.what() << "\n";
      }
      outcome.success = outcome.correct && outcome.claimed;
      stats->outcomes.push_back(outcome);
      if (stats != &ours)
        continue;
      digest.add(result);
      by_type[view.type.name].outcomes.push_back(outcome);
      by_layout[std::to_string(view.faces_wanted) + " (" + view.layout + ")"].outcomes.push_back(outcome);
      std::ostringstream line;
      line << "view " << index << " " << view.type.name << " " << view.layout << " (" << view.faces_seen
           << " faces seen) at " << view.distance_m << " m, " << view.scan.size() << " points: " << outcome.rotation_deg
           << " deg, " << outcome.translation_mm << " mm, " << outcome.cpu_ms << " ms CPU, coverage scan "
           << result.view.target_coverage << " model " << result.view.model_coverage << " free-space "
           << result.view.free_space_violation << ", confidence " << result.confidence << ", " << result.bases_tried
           << " bases, " << result.candidates_verified << " candidates, " << (result.success ? "success" : "unsure")
           << ": " << result.reason;
      if (outcome.claimed && !outcome.correct)
        wrong.push_back(line.str());
      else if (!outcome.claimed && outcome.correct)
        unsure_right.push_back(line.str());
      if (options.verbose)
      {
        std::cerr << line.str() << "\n";
        // The error rotation's axis in the brick frame, for the closest symmetry.
        double best_angle = 1e9;
        Eigen::AngleAxisd best_error;
        Eigen::Vector3d offset_brick = Eigen::Vector3d::Zero();
        for (const Eigen::Isometry3d& symmetry : symmetries)
        {
          const Eigen::Isometry3d equivalent = view.camera_T_brick * symmetry;
          const Eigen::AngleAxisd error(Eigen::Matrix3d(equivalent.linear().transpose() * result.source_to_target.linear()));
          if (error.angle() < best_angle)
          {
            best_angle = error.angle();
            best_error = error;
            offset_brick = equivalent.inverse() * result.source_to_target.translation();
          }
        }
        std::cerr << "  error axis (brick frame, of the matched symmetry) " << best_error.axis().transpose()
                  << ", origin offset (mm) " << 1e3 * offset_brick.transpose() << "\n";
      }
    }
    if ((index + 1) % 20 == 0)
      std::cerr << "bench_registration: " << (index + 1) << "/" << options.views << " views\n";
  }

  std::printf("\n## Registration of whole-cuboid views (synthetic D415, 0.6-2 m)\n\n");
  std::printf("%d views of a whole cuboid model (1 cm grid, all six faces, normals) onto the brick's pixels "
              "(noisy depth, holes, flying pixels; at most 3000 points, median %.0f), types: the catalogue's and a "
              "0.40 x 0.30 x 0.20 m cardboard box; %d camera poses redrawn because the brick left the image. "
              "Success: claimed and right (rotation < %.0f deg, translation < %.0f mm modulo the cuboid's true "
              "symmetries); false success: claimed and wrong. PCL registers the scan onto the model (overlap 0.9, "
              "%d s cap); it claims success when it converges.\n\n",
              options.views, percentile(scan_sizes, 0.5), redraws, kSuccessRotationDeg, 1e3 * kSuccessTranslationM,
              options.pcl_time_s);
  printHeader("method");
  for (const MethodStats* stats : {&ours, &fpcs, &kfpcs})
    if (!stats->outcomes.empty())
      printRow(stats->name, *stats);
  std::printf("\nSuper4PCS whole view by faces (layout):\n\n");
  printHeader("faces");
  for (const auto& [name, stats] : by_layout)
    printRow(name, stats);
  std::printf("\nSuper4PCS whole view by type:\n\n");
  printHeader("type");
  for (const auto& [name, stats] : by_type)
    printRow(name, stats);
  const auto search_cpu = quantiles(ours, &Outcome::search_cpu_ms);
  const auto refine_cpu = quantiles(ours, &Outcome::refine_cpu_ms);
  std::printf("\nSuper4PCS whole view CPU by phase, median / p95 (ms): search %.1f / %.1f, refinement and checks "
              "%.1f / %.1f.\n",
              search_cpu.first, search_cpu.second, refine_cpu.first, refine_cpu.second);
  std::printf("\nClaimed and wrong (%zu):\n", wrong.size());
  for (const std::string& line : wrong)
    std::printf("- %s\n", line.c_str());
  std::printf("\nRight but not claimed (%zu):\n", unsure_right.size());
  for (const std::string& line : unsure_right)
    std::printf("- %s\n", line.c_str());

  const Summary s = summarise(ours);
  std::ostringstream json;
  json.setf(std::ios::fixed);
  json.precision(4);
  json << "\"views\": " << options.views << ", \"s4pcs_views_success\": " << s.success
       << ", \"s4pcs_views_false_success\": " << s.false_successes << ", \"s4pcs_views_median_ms\": " << s.median_cpu_ms
       << ", \"s4pcs_views_p95_ms\": " << s.p95_cpu_ms << ", \"s4pcs_views_median_wall_ms\": " << s.median_ms
       << ", \"s4pcs_views_p95_wall_ms\": " << s.p95_ms << ", \"s4pcs_views_median_rot_deg\": "
       << s.median_rotation_deg << ", \"s4pcs_views_median_trans_mm\": " << s.median_translation_mm
       << ", \"s4pcs_views_digest\": \"" << std::hex << digest.value() << std::dec << "\"";
  for (const MethodStats* stats : {&fpcs, &kfpcs})
    if (!stats->outcomes.empty())
    {
      const Summary p = summarise(*stats);
      json << ", \"" << stats->json_key << "_success\": " << p.success << ", \"" << stats->json_key
           << "_false_success\": " << p.false_successes << ", \"" << stats->json_key
           << "_median_ms\": " << p.median_cpu_ms << ", \"" << stats->json_key << "_median_wall_ms\": " << p.median_ms;
    }
  return json.str();
}
}  // namespace bench_registration
