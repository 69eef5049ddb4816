#include "bench_frontend/setup.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace frontend_bench
{
namespace
{
std::optional<sim::SceneKind> rigKind(const std::string& name)
{
  try
  {
    return sim::sceneKindFromString(name);
  }
  catch (const ConfigError&)
  {
    return std::nullopt;
  }
}

std::optional<SegmentationMode> frontEndMode(const std::string& name)
{
  try
  {
    return parseSegmentationMode(name);
  }
  catch (const ConfigError&)
  {
    return std::nullopt;
  }
}

/// The 1280x720 intrinsics scaled by 2/3 (853x480) and cropped about the
/// centre to `width_px`, as the D415 derives its 480-line colour modes.
PinholeCamera d415Color480(int width_px)
{
  PinholeCamera camera = PinholeCamera::d415Color1280x720().scaled(2.0 / 3.0);
  camera.cx_px -= 0.5 * (camera.width_px - width_px);
  camera.width_px = width_px;
  return camera;
}
}  // namespace

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--frames" && has_value) options.frames = std::max(1, std::atoi(argv[++i]));
    else if (arg == "--seed" && has_value) options.seed = std::strtoull(argv[++i], nullptr, 10);
    else if (arg == "--mosd" && has_value) options.mosd_dir = argv[++i];
    else if (arg == "--mosd-catalogue" && has_value) options.mosd_catalogue = argv[++i];
    else if (arg == "--no-mosd") options.skip_mosd = true;
    else if (arg == "--no-rig") options.skip_rig = true;
    else if (arg == "--verbose") options.verbose = true;
    else if (arg == "--overlay-dir" && has_value) options.overlay_dir = argv[++i];
    else
    {
      std::cerr << "usage: bench_frontend [--frames N] [--seed S] [--mosd DIR] [--mosd-catalogue FILE] [--no-mosd] "
                   "[--no-rig] [--verbose] [--overlay-dir DIR]\n";
      std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
    }
  }
  if (std::getenv("BENCH_VERBOSE")) options.verbose = true;
  return options;
}

std::vector<SceneClass> sceneClasses()
{
  // One line per class: report label, rig scene kind, legacy sequence.
  std::vector<SceneClass> classes = {
      {"singles", "single", true, std::nullopt},
      {"gapped piles (organised)", "organised_pile", true, std::nullopt},
      {"unorganised piles", "unorganised_pile", true, std::nullopt},
      {"touching rows", "touching_row", false, std::nullopt},
      {"pallet layers", "pallet_layer", false, std::nullopt},
      {"oblique table views", "oblique_table", false, std::nullopt},
  };
  for (SceneClass& scene_class : classes) scene_class.kind = rigKind(scene_class.rig_kind);
  return classes;
}

std::vector<Resolution> resolutions()
{
  return {{"1280x720", PinholeCamera::d415Color1280x720(), true},
          {"848x480", d415Color480(848), false},
          {"640x480", d415Color480(640), false}};
}

std::vector<ModeSpec> modes()
{
  std::vector<ModeSpec> specs = {
      {"hsv", std::nullopt, false, false},
      {"region_growing", std::nullopt, true, false},
      {"colour_free", std::nullopt, true, true},
  };
  for (ModeSpec& spec : specs) spec.mode = frontEndMode(spec.name);
  return specs;
}

const ModeSpec* headlineColourFreeMode(const std::vector<ModeSpec>& modes)
{
  const ModeSpec* fallback = nullptr;
  for (const ModeSpec& mode : modes)
  {
    if (!mode.colour_free || !mode.mode) continue;
    if (mode.preferred_colour_free) return &mode;
    if (!fallback) fallback = &mode;
  }
  return fallback;
}

FrontEndParams frontEndParamsFor(const ModeSpec& mode, const Eigen::Vector3d& up_in_camera)
{
  FrontEndParams params;
  params.mode = *mode.mode;
  if (mode.colour_free) params.roi.up_direction = up_in_camera;
  return params;
}

std::vector<FrameSpec> framePlan(const std::vector<SceneClass>& classes, const Options& options)
{
  static const sim::Lighting kLightings[3] = {sim::Lighting::kNormal, sim::Lighting::kSunlight,
                                              sim::Lighting::kLowLight};
  std::vector<std::size_t> legacy_classes;
  for (std::size_t c = 0; c < classes.size(); ++c)
    if (classes[c].legacy && classes[c].kind) legacy_classes.push_back(c);
  std::vector<FrameSpec> plan;
  if (options.skip_rig) return plan;
  // The earlier benchmark: singles at i % 4 == 0, 1, organised piles at 2,
  // unorganised at 3; lighting changes every four frames.
  if (legacy_classes.size() == 3)
    for (int i = 0; i < options.frames; ++i)
    {
      FrameSpec frame;
      frame.scene_class = legacy_classes[i % 4 == 3 ? 2 : (i % 4 == 2 ? 1 : 0)];
      frame.seed = options.seed * 1000003ULL + static_cast<std::uint64_t>(i);
      frame.lighting = kLightings[(i / 4) % 3];
      frame.legacy = true;
      plan.push_back(frame);
    }
  const int extra_frames = std::max(1, options.frames / 4);
  for (std::size_t c = 0; c < classes.size(); ++c)
  {
    if (classes[c].legacy || !classes[c].kind) continue;
    for (int j = 0; j < extra_frames; ++j)
    {
      FrameSpec frame;
      frame.scene_class = c;
      // Seeds apart from the legacy sequence's (index < 10^6).
      frame.seed = options.seed * 1000003ULL + 1000000ULL * (c + 1) + static_cast<std::uint64_t>(j);
      frame.lighting = kLightings[j % 3];
      plan.push_back(frame);
    }
  }
  return plan;
}

sim::SceneParams sceneParamsFor(const SceneClass& scene_class)
{
  sim::SceneParams params;
  params.kind = *scene_class.kind;
  params.min_distance_m = 0.5;
  params.max_distance_m = 2.0;
  return params;
}
}  // namespace frontend_bench
}  // namespace brick_pose
