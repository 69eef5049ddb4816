#include "bench_frontend/setup.h"

#include <algorithm>
#include <cstdlib>
#include <iostream>

#include "brick_pose/common/errors.h"
#include "brick_pose/sim/d415_modes.h"

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

std::vector<std::string> commaList(const std::string& text)
{
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size())
  {
    const std::size_t end = std::min(text.find(',', start), text.size());
    if (end > start) items.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return items;
}
}  // namespace

bool allowedBy(const std::vector<std::string>& allowed, const std::string& name)
{
  return allowed.empty() || std::find(allowed.begin(), allowed.end(), name) != allowed.end();
}

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
    else if (arg == "--box-catalogue" && has_value) options.box_catalogue = argv[++i];
    else if (arg == "--no-mosd") options.skip_mosd = true;
    else if (arg == "--no-rig") options.skip_rig = true;
    else if (arg == "--verbose") options.verbose = true;
    else if (arg == "--measured-corners") options.measured_corners = true;
    else if (arg == "--repeat" && has_value) options.repeat = std::max(0, std::atoi(argv[++i]));
    else if (arg == "--overlay-dir" && has_value) options.overlay_dir = argv[++i];
    else if (arg == "--frame" && has_value) options.only_frame = std::atoi(argv[++i]);
    else if (arg == "--only" && i + 3 < argc)
    {
      options.only_kinds = commaList(argv[++i]);
      options.only_modes = commaList(argv[++i]);
      options.only_resolutions = commaList(argv[++i]);
    }
    else
    {
      std::cerr << "usage: bench_frontend [--frames N] [--seed S] [--mosd DIR] [--mosd-catalogue FILE] [--box-catalogue FILE] "
                   "[--no-mosd] "
                   "[--no-rig] [--verbose] [--measured-corners] [--repeat N] [--overlay-dir DIR] [--only KINDS MODES RESOLUTIONS] [--frame N]\n";
      std::exit(arg == "--help" || arg == "-h" ? 0 : 2);
    }
  }
  if (std::getenv("BENCH_VERBOSE")) options.verbose = true;
  return options;
}

std::vector<SceneClass> sceneClasses()
{
  // One line per class: report label, rig scene kind, legacy sequence.
  using C = ClassCatalogue;
  // One line per class: report label, rig scene kind, legacy sequence,
  // catalogue, depth model.
  std::vector<SceneClass> classes = {
      {"singles", "single", true, C::kBricks, "ideal", std::nullopt},
      {"gapped piles (organised)", "organised_pile", true, C::kBricks, "ideal", std::nullopt},
      {"unorganised piles", "unorganised_pile", true, C::kBricks, "ideal", std::nullopt},
      {"touching rows (bricks)", "touching_rows", false, C::kBricks, "d4xx", std::nullopt},
      {"pallet layers (boxes)", "pallet_layer", false, C::kBoxes, "d4xx", std::nullopt},
      {"pallet stacks (boxes)", "pallet_stack", false, C::kBoxes, "d4xx", std::nullopt},
      {"oblique table views (boxes)", "table_boxes", false, C::kBoxes, "d4xx", std::nullopt},
  };
  for (SceneClass& scene_class : classes) scene_class.kind = rigKind(scene_class.rig_kind);
  return classes;
}

std::vector<Resolution> resolutions()
{
  return {{"1280x720", sim::d415ColourMode("1280x720"), true},
          {"848x480", sim::d415ColourMode("848x480"), false},
          {"640x480", sim::d415ColourMode("640x480"), false}};
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

FrontEndParams frontEndParamsFor(const ModeSpec& mode, const Eigen::Vector3d& up_in_camera,
                                 const Eigen::Vector4d& support_plane, bool measured_corners)
{
  FrontEndParams params;
  params.mode = *mode.mode;
  params.roi.place_on_catalogue_size = !measured_corners;
  if (mode.colour_free) params.roi.up_direction = up_in_camera;
  if (mode.colour_free) params.roi.support_plane = support_plane;
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
  if (!scene_class.legacy) return sim::SceneParams::defaultsFor(*scene_class.kind);
  sim::SceneParams params;
  params.kind = *scene_class.kind;
  params.min_distance_m = 0.5;
  params.max_distance_m = 2.0;
  return params;
}

sim::SensorModel sensorFor(const SceneClass& scene_class, sim::Lighting lighting)
{
  sim::SensorModel sensor = sim::depthModelFromString(scene_class.depth_model) == sim::DepthModel::kD4xx
                                ? sim::SensorModel::d4xx()
                                : sim::SensorModel();
  sensor.lighting = lighting;
  return sensor;
}

std::string modeNotApplicable(const ModeSpec& mode, const BrickCatalogue& catalogue)
{
  if (!mode.mode) return "the front end lacks it";
  if (*mode.mode != SegmentationMode::kHsv) return "";
  for (const BrickType& type : catalogue.types())
    if (type.hasPlateColour()) return "";
  return "no type has a plate colour";
}
}  // namespace frontend_bench
}  // namespace brick_pose
