#include "brick_pose/sim/rig_config.h"

#include <cmath>
#include <sstream>

#include "brick_pose/common/errors.h"
#include "brick_pose/sim/d415_modes.h"

namespace brick_pose
{
namespace sim
{
const std::vector<std::pair<std::string, std::string>>& rigParameterHelp()
{
  static const std::vector<std::pair<std::string, std::string>> help = {
      {"catalogue_path", "brick catalogue YAML (default: built-in MBZIRC 2020 bricks)"},
      {"scene", "single | organised_pile | unorganised_pile | touching_rows | pallet_layer | pallet_stack | "
                "table_boxes (default single); the kind sets its own default distances, view angles and counts"},
      {"types", "comma-separated brick types to draw from (default: all)"},
      {"seed", "scene seed; the same seed gives the same scene and noise (default 1)"},
      {"min_distance_m", "nearest camera-to-pile distance (default 0.6)"},
      {"max_distance_m", "farthest camera-to-pile distance (default 1.5)"},
      {"view", "top (elevation 65-89 deg) | oblique (20-60 deg: 30-70 deg from the vertical); "
               "min/max_elevation_deg override it"},
      {"min_elevation_deg", "lowest view angle below the horizon (default 55)"},
      {"max_elevation_deg", "highest view angle, 90 = straight down (default 88)"},
      {"max_tilt_deg", "largest brick tilt (default 8)"},
      {"max_pile_bricks", "bricks in an unorganised pile: 2..this (default 6)"},
      {"max_rows", "rows of an organised pile or of touching rows: 1..this (default 3; touching_rows 4)"},
      {"max_layers", "layers of an organised pile, touching rows or a pallet stack (default 2; touching_rows 1, "
                     "pallets 3)"},
      {"max_gap_m", "touching rows and pallets: widest seam between neighbours (default 0.003)"},
      {"zero_gap_probability", "touching rows and pallets: chance that a seam is closed (default 0.5)"},
      {"max_row_length_m", "touching rows: bricks end to end up to this length (default 2.0)"},
      {"pallet_length_m", "pallet footprint length (default 1.2)"},
      {"pallet_width_m", "pallet footprint width (default 0.8)"},
      {"missing_box_probability", "pallets: chance that a box of a layer is missing (default 0.08)"},
      {"layer_offset_m", "pallet stacks: largest shift of an upper layer (default 0.05)"},
      {"max_table_boxes", "table boxes: 1..this boxes (default 4)"},
      {"upright_probability", "table boxes: chance that a box stands on a side or an end (default 0.7)"},
      {"stack_probability", "table boxes: chance that a box is put on an earlier one (default 0.3)"},
      {"markings", "paint types without a plate colour as cardboard with tape, labels and barcodes (default true)"},
      {"edge_radius_m", "radius of the rounded top edges: a crease in depth, a dark line in colour at seams "
                        "(default 0; the box kinds 0.004)"},
      {"lighting", "normal | sunlight | low_light (default normal)"},
      {"resolution", "D415 colour mode with its intrinsics: 1280x720 | 848x480 | 640x480 | 640x360 | 1920x1080 "
                     "(default 1280x720); width, height, fx, fy, cx, cy override it"},
      {"width", "image width in pixels (default 1280)"},
      {"height", "image height in pixels (default 720)"},
      {"fx", "focal length x in pixels (default 920)"},
      {"fy", "focal length y in pixels (default 920)"},
      {"cx", "principal point x (default 640)"},
      {"cy", "principal point y (default 360)"},
      {"baseline_m", "stereo baseline (default 0.055)"},
      {"subpixel_px", "stereo subpixel accuracy (default 0.08)"},
      {"dropout_probability", "random depth holes per pixel (default 0.002)"},
      {"flying_pixel_probability", "chance of a flying pixel on a depth edge (default 0.5)"},
      {"stereo_shadow", "holes where the second imager is occluded (default true)"},
      {"depth_model", "ideal | d4xx: d4xx sets the four below to a D4xx's values (7, 3, 1/32, 2 and 1) "
                      "(default ideal: all off)"},
      {"stereo_window_px", "stereo matching window (odd; 1 = off): smooths depth over seams and narrow gaps"},
      {"edge_fattening_px", "pixels the nearer surface grows into the farther at a depth step (0 = off)"},
      {"disparity_step_px", "disparity quantisation step in pixels, e.g. 0.03125 (0 = off)"},
      {"depth_offset_u_px", "misregistration of the aligned depth against colour, x (pixels)"},
      {"depth_offset_v_px", "misregistration of the aligned depth against colour, y (pixels)"},
  };
  return help;
}

namespace
{

void readCamera(const ParamReader& read, PinholeCamera& camera)
{
  if (const auto resolution = read.text("resolution")) camera = d415ColourMode(*resolution);
  readBound(read, {{"width", &camera.width_px}, {"height", &camera.height_px}, {"fx", &camera.fx_px},
                   {"fy", &camera.fy_px}, {"cx", &camera.cx_px}, {"cy", &camera.cy_px}});
  camera.validate();
}

void readSensor(const ParamReader& read, SensorModel& sensor)
{
  // The preset first: the other parameters override it.
  if (const auto model = read.text("depth_model"))
    sensor = depthModelFromString(*model) == DepthModel::kD4xx ? SensorModel::d4xx() : SensorModel();
  if (const auto lighting = read.text("lighting")) sensor.lighting = lightingFromString(*lighting);
  readBound(read, {{"baseline_m", &sensor.baseline_m},
                   {"subpixel_px", &sensor.subpixel_px},
                   {"dropout_probability", &sensor.dropout_probability},
                   {"flying_pixel_probability", &sensor.flying_pixel_probability},
                   {"stereo_shadow", &sensor.stereo_shadow},
                   {"stereo_window_px", &sensor.stereo_window_px},
                   {"edge_fattening_px", &sensor.edge_fattening_px},
                   {"disparity_step_px", &sensor.disparity_step_px},
                   {"depth_offset_u_px", &sensor.depth_offset_u_px},
                   {"depth_offset_v_px", &sensor.depth_offset_v_px}});
  sensor.validate();
}

ParamBindings sceneBindings(SceneParams& scene)
{
  return {{"min_distance_m", &scene.min_distance_m},
          {"max_distance_m", &scene.max_distance_m},
          {"min_elevation_deg", &scene.min_elevation_deg},
          {"max_elevation_deg", &scene.max_elevation_deg},
          {"max_tilt_deg", &scene.max_tilt_deg},
          {"max_pile_bricks", &scene.max_pile_bricks},
          {"max_rows", &scene.max_rows},
          {"max_layers", &scene.max_layers},
          {"max_gap_m", &scene.max_gap_m},
          {"zero_gap_probability", &scene.zero_gap_probability},
          {"max_row_length_m", &scene.max_row_length_m},
          {"pallet_length_m", &scene.pallet_length_m},
          {"pallet_width_m", &scene.pallet_width_m},
          {"missing_box_probability", &scene.missing_box_probability},
          {"layer_offset_m", &scene.layer_offset_m},
          {"max_table_boxes", &scene.max_table_boxes},
          {"upright_probability", &scene.upright_probability},
          {"stack_probability", &scene.stack_probability},
          {"edge_radius_m", &scene.edge_radius_m},
          {"markings", &scene.markings}};
}

void readScene(const ParamReader& read, SceneParams& scene)
{
  // The kind first: its defaults are what the other parameters override.
  if (const auto kind = read.text("scene")) scene = SceneParams::defaultsFor(sceneKindFromString(*kind));
  if (const auto types = read.text("types")) scene.types = splitList(*types);
  if (const auto view = read.text("view")) scene.applyView(*view);
  readBound(read, sceneBindings(scene));
}
}  // namespace

RigConfig rigConfigFrom(const ParamLookup& lookup)
{
  const ParamReader read(lookup);
  RigConfig config;
  if (const auto path = read.text("catalogue_path"))
    if (!path->empty()) config.catalogue = BrickCatalogue::fromYamlFile(*path);
  readCamera(read, config.camera);
  readSensor(read, config.sensor);
  readScene(read, config.scene);
  config.scene.validate(config.catalogue);
  if (const auto seed = read.text("seed"))
  {
    const long long value = parseInteger("seed", *seed);
    if (value < 0) throw ConfigError("parameter 'seed': must be >= 0");
    config.seed = static_cast<std::uint64_t>(value);
  }
  return config;
}
}  // namespace sim
}  // namespace brick_pose
