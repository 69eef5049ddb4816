// The measured ground truth of the mOSD learn scenes, for inspection and to
// bound its error:
//  1. per scene and box: faces by role, the top's size, height, fill and
//     whether it is whole in view;
//  2. the boxes grouped by size over the scenes (the same box recurs): each
//     group's spread bounds the measurement's repeatability, and the groups
//     are the mOSD catalogue (--write-catalogue writes it);
//  3. the same extraction on synthetic rig frames dressed as mOSD scenes,
//     against the rig's exact truth (--rig-check N frames).
//
//   bench_mosd_truth [--data DIR] [--overlay-dir DIR] [--write-catalogue FILE] [--rig-check N]
//
// With --overlay-dir, writes <scene>_truth.png per scene (colours: see
// drawMosdTruthOverlay).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "brick_pose/common/statistics.h"
#include "brick_pose/eval/mosd_catalogue.h"
#include "brick_pose/eval/mosd_scene.h"
#include "brick_pose/eval/mosd_truth.h"
#include "brick_pose/eval/rig_as_mosd.h"
#include "brick_pose/eval/rig_truth.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/synthetic_rig.h"

using namespace brick_pose;

namespace
{
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

struct Options
{
  std::string data_dir = eval::mosdLearnDirectory(BRICK_POSE_SOURCE_DIR);
  std::string overlay_dir;
  std::string catalogue_path;
  int rig_frames = 0;
};

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--data" && has_value) options.data_dir = argv[++i];
    else if (arg == "--overlay-dir" && has_value) options.overlay_dir = argv[++i];
    else if (arg == "--write-catalogue" && has_value) options.catalogue_path = argv[++i];
    else if (arg == "--rig-check" && has_value) options.rig_frames = std::max(0, std::atoi(argv[++i]));
    else
    {
      std::cerr << "usage: bench_mosd_truth [--data DIR] [--overlay-dir DIR] [--write-catalogue FILE] "
                   "[--rig-check N]\n";
      std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
    }
  }
  return options;
}

int facesWithRole(const eval::MosdBox& box, eval::FaceRole role)
{
  int count = 0;
  for (const eval::MosdFace& face : box.faces) count += face.role == role ? 1 : 0;
  return count;
}

void printBox(const std::string& scene, const eval::MosdBox& box)
{
  std::printf("%-8s %3d %5zu %5zu %5d %5d | ", scene.c_str(), box.object, box.pixels.size(),
              box.has_top ? box.faces[static_cast<std::size_t>(box.top_face)].pixels.size() : 0,
              facesWithRole(box, eval::FaceRole::kSide),
              facesWithRole(box, eval::FaceRole::kOther) + facesWithRole(box, eval::FaceRole::kBottom));
  if (!box.has_top)
  {
    std::printf("%7s %7s %7s %7.0f | %5s %5s | no top face seen\n", "-", "-", "-", 1000.0 * box.visible_height_m, "-",
                "-");
    return;
  }
  std::printf("%7.1f %7.1f %7.1f %7.1f | %5.2f %5d | %s\n", 1000.0 * box.top.length_m, 1000.0 * box.top.width_m,
              1000.0 * box.height_m, 1000.0 * box.visible_height_m, box.top_fill, box.occluder_px,
              box.top_whole ? "whole" : box.not_whole_reason.c_str());
}

void printGroups(const std::vector<eval::MosdBoxGroup>& groups)
{
  std::printf("\n== Boxes grouped by size over the scenes (the catalogue; size = median of the whole tops)\n");
  std::printf("%-22s %3s %5s | %21s | %s\n", "type", "n", "whole", "spread L / W / H mm", "scenes");
  for (const eval::MosdBoxGroup& group : groups)
  {
    int whole = 0;
    std::string scenes;
    for (const eval::MosdTopMeasurement& member : group.members)
    {
      whole += member.whole ? 1 : 0;
      scenes += " " + member.scene + "/" + std::to_string(member.object);
    }
    std::printf("%-22s %3zu %5d | %6.1f %6.1f %6.1f | %s\n", group.type.name.c_str(), group.members.size(), whole,
                1000.0 * group.length_spread_m, 1000.0 * group.width_spread_m, 1000.0 * group.height_spread_m,
                scenes.c_str());
  }
}

/// Cuboids of the sizes of the mOSD boxes (standing and lying), for the rig check.
BrickCatalogue rigCheckCatalogue()
{
  return BrickCatalogue::fromYamlString(R"(bricks:
  - {name: upright, length_m: 0.15, width_m: 0.06, height_m: 0.24, plate_rgb: [220, 180, 40], body_rgb: [200, 60, 50], hsv_min: [0, 0, 0], hsv_max: [180, 255, 255]}
  - {name: flat, length_m: 0.20, width_m: 0.13, height_m: 0.05, plate_rgb: [60, 120, 200], body_rgb: [230, 230, 230], hsv_min: [0, 0, 0], hsv_max: [180, 255, 255]}
  - {name: cube, length_m: 0.08, width_m: 0.07, height_m: 0.15, plate_rgb: [90, 170, 60], body_rgb: [240, 200, 60], hsv_min: [0, 0, 0], hsv_max: [180, 255, 255]}
)");
}

/// The extraction on rig frames against the exact truth.
void rigCheck(int frames)
{
  const BrickCatalogue catalogue = rigCheckCatalogue();
  PinholeCamera camera;  // the mOSD Kinect's intrinsics
  camera.width_px = 640;
  camera.height_px = 480;
  camera.fx_px = camera.fy_px = 525.0;
  camera.cx_px = 319.5;
  camera.cy_px = 239.5;
  std::vector<sim::SceneGenerator> generators;
  for (const sim::SceneKind kind : {sim::SceneKind::kSingle, sim::SceneKind::kUnorganisedPile})
  {
    sim::SceneParams params;
    params.kind = kind;
    params.min_distance_m = 0.7;
    params.max_distance_m = 1.3;
    params.min_elevation_deg = 35.0;  // oblique, like the mOSD views
    params.max_elevation_deg = 70.0;
    params.max_pile_bricks = 3;
    generators.emplace_back(catalogue, params);
  }
  std::vector<double> length_mm, width_mm, height_mm, centre_mm, normal_deg;
  int agree = 0, truth_whole_only = 0, extracted_whole_only = 0, tops = 0, missed_tops = 0;
  for (int i = 0; i < frames; ++i)
  {
    const std::uint64_t seed = 7000 + static_cast<std::uint64_t>(i);
    const sim::Scene scene = generators[static_cast<std::size_t>(i % 2)].generate(seed);
    const sim::SyntheticFrame frame = sim::SyntheticRig(camera, sim::SensorModel()).render(scene, seed);
    const Eigen::Vector3d up = scene.world_T_camera.linear().transpose() * Eigen::Vector3d::UnitZ();
    const eval::SceneTruth exact = eval::rigSceneTruth(frame, up);
    const eval::MosdTruth measured = eval::extractMosdTruth(eval::mosdSceneFromRig(frame, "rig" + std::to_string(i)));
    for (const sim::BrickTruth& brick : frame.truth)
    {
      const eval::FaceTruth& exact_top = exact.faces[static_cast<std::size_t>((brick.instance_id - 1) * 6)];
      if (exact_top.role != eval::FaceRole::kTop || brick.visible_top_pixels < 150) continue;
      ++tops;
      const eval::MosdBox* box = nullptr;
      for (const eval::MosdBox& candidate : measured.boxes)
        if (candidate.object == eval::mosdObjectOfRigInstance(brick.instance_id)) box = &candidate;
      if (!box || !box->has_top)
      {
        ++missed_tops;
        continue;
      }
      const bool measured_whole = box->top_whole;
      if (measured_whole == exact_top.whole_in_view) ++agree;
      else if (exact_top.whole_in_view) ++truth_whole_only;
      else ++extracted_whole_only;
      if (!(measured_whole && exact_top.whole_in_view)) continue;
      length_mm.push_back(1000.0 * (box->top.length_m - brick.dimensions_m.x()));
      width_mm.push_back(1000.0 * (box->top.width_m - brick.dimensions_m.y()));
      height_mm.push_back(1000.0 * (box->height_m - brick.dimensions_m.z()));
      centre_mm.push_back(1000.0 * (box->top.centre_m - brick.camera_T_brick.translation()).norm());
      const Eigen::Vector3d true_normal = brick.camera_T_brick.linear().col(2);
      normal_deg.push_back(std::atan2(box->top.normal.cross(true_normal).norm(), box->top.normal.dot(true_normal)) *
                           kDegPerRad);
    }
  }
  auto row = [](const char* name, const std::vector<double>& values, const char* unit) {
    std::vector<double> magnitude;
    for (const double value : values) magnitude.push_back(std::abs(value));
    std::printf("  %-14s median %+6.2f  |median| %5.2f  |p95| %5.2f %s (n = %zu)\n", name, percentile(values, 0.5),
                percentile(magnitude, 0.5), percentile(magnitude, 0.95), unit, values.size());
  };
  std::printf("\n== The extraction on %d rig frames dressed as mOSD (640x480, fx 525, D415 noise, 0.7-1.3 m, "
              "35-70 deg elevation, singles and piles of up to 3 boxes of mOSD sizes)\n",
              frames);
  std::printf("  tops with >= 150 visible px: %d; no top extracted: %d\n", tops - 0, missed_tops);
  std::printf("  whole in view: verdicts agree %d; exact truth whole but extracted not: %d; extracted whole but "
              "exact truth not: %d\n",
              agree, truth_whole_only, extracted_whole_only);
  std::printf("  errors on tops both call whole (measured - true):\n");
  row("length", length_mm, "mm");
  row("width", width_mm, "mm");
  row("height", height_mm, "mm");
  row("centre", centre_mm, "mm");
  row("normal", normal_deg, "deg");
}
}  // namespace

int main(int argc, char** argv)
{
  const Options options = parseOptions(argc, argv);
  int tops = 0, whole = 0, uncertain = 0;
  std::printf("%-8s %3s %5s %5s %5s %5s | %7s %7s %7s %7s | %5s %5s | %s\n", "scene", "obj", "px", "top", "side",
              "other", "L mm", "W mm", "H mm", "visH mm", "fill", "occl", "verdict");
  std::vector<std::unique_ptr<eval::MosdScene>> scenes;
  std::vector<eval::MosdTopMeasurement> measurements;
  for (const std::string& name : eval::mosdSceneNames(options.data_dir))
  {
    scenes.push_back(std::make_unique<eval::MosdScene>(eval::loadMosdScene(options.data_dir, name)));
    const eval::MosdScene& scene = *scenes.back();
    const eval::MosdTruth truth = eval::extractMosdTruth(scene);
    for (const eval::MosdBox& box : truth.boxes)
    {
      printBox(name, box);
      if (!box.has_top) continue;
      ++tops;
      whole += box.top_whole ? 1 : 0;
      uncertain += box.top_uncertain ? 1 : 0;
    }
    for (eval::MosdTopMeasurement& measurement : eval::topMeasurements(scene, truth))
      measurements.push_back(std::move(measurement));
    if (!options.overlay_dir.empty())
      cv::imwrite(options.overlay_dir + "/" + name + "_truth.png", eval::drawMosdTruthOverlay(scene, truth));
  }
  std::printf("\n%d top faces seen: %d whole in view, %d uncertain, %d not whole\n", tops, whole, uncertain,
              tops - whole - uncertain);

  std::vector<const eval::MosdScene*> scene_views;
  for (const auto& scene : scenes) scene_views.push_back(scene.get());
  const std::vector<eval::MosdBoxGroup> groups = eval::groupMosdBoxes(measurements, scene_views);
  printGroups(groups);
  if (!options.catalogue_path.empty())
  {
    // Only boxes seen whole at least once: the size of one only ever seen
    // partly hidden is not measured (and its whole top is never scored).
    std::vector<BrickType> types;
    for (const eval::MosdBoxGroup& group : groups)
      if (std::any_of(group.members.begin(), group.members.end(),
                      [](const eval::MosdTopMeasurement& member) { return member.whole; }))
        types.push_back(group.type);
    std::ofstream(options.catalogue_path) << eval::catalogueYaml(
        types,
        "The boxes of the mOSD learn scenes, measured from the scenes' labels by\n"
        "bench_mosd_truth --write-catalogue (include/brick_pose/eval/mosd_catalogue.h):\n"
        "one type per box size (a box standing and lying is two types), the size the\n"
        "median of its whole tops; boxes never seen whole are left out (their size is\n"
        "not measured). The HSV ranges are fitted to the printed tops\n"
        "(80% of their hues, 10-90th percentile of S and V); they are wide because\n"
        "the tops are printed in several colours. Regenerate, do not edit by hand.");
    std::printf("\ncatalogue of %zu types written to %s\n", types.size(), options.catalogue_path.c_str());
  }
  if (options.rig_frames > 0) rigCheck(options.rig_frames);
  return 0;
}
