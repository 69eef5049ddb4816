#pragma once
// Seeded scenes for the synthetic rig: single bricks, organised piles (rows
// and stacked layers with 1-3 cm gaps), unorganised piles (bricks dropped
// onto each other), and the cases real piles show and the rig used to miss:
// rows of touching bricks, pallet layers of touching boxes of mixed sizes,
// stacked pallet layers with offsets, and boxes standing on a table seen
// obliquely.

#include <cstdint>
#include <string>
#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/sim/scene.h"

namespace brick_pose
{
namespace sim
{
enum class SceneKind
{
  kSingle,
  kOrganisedPile,
  kUnorganisedPile,
  /// One type, rows side by side and bricks end to end, every seam either
  /// closed (zero gap) or 0..max_gap_m wide; max_layers exactly stacked layers.
  kTouchingRows,
  /// One layer of boxes of mixed sizes packed on a pallet footprint in strips,
  /// most touching (seams 0..max_gap_m), a few missing.
  kPalletLayer,
  /// 2..max_layers pallet layers, each shifted by up to layer_offset_m and
  /// the upper ones partly filled, so lower tops are partly covered.
  kPalletStack,
  /// 1..max_table_boxes boxes on a table, most standing on a side or an end
  /// (catalogue top face vertical), some stacked, seen obliquely.
  kTableBoxes,
};

/// "single", "organised_pile", "unorganised_pile", "touching_rows",
/// "pallet_layer", "pallet_stack", "table_boxes"; throws ConfigError otherwise.
SceneKind sceneKindFromString(const std::string& name);
std::string toString(SceneKind kind);

struct SceneParams
{
  SceneKind kind = SceneKind::kSingle;
  /// Brick types to draw from; empty means every type of the catalogue.
  std::vector<std::string> types;
  /// Distance from the camera to the pile's top centre.
  double min_distance_m = 0.6;
  double max_distance_m = 1.5;
  /// Angle of the optical axis below the horizon (90 = looking straight down).
  double min_elevation_deg = 55.0;
  double max_elevation_deg = 88.0;
  /// Largest tilt of a single brick or of a dropped brick.
  double max_tilt_deg = 8.0;
  int max_pile_bricks = 6;  // unorganised piles draw 2..max
  int max_rows = 3;         // organised piles, touching rows
  int max_layers = 2;       // organised piles, touching rows, pallet stacks

  // Touching rows and pallets: each seam is closed with zero_gap_probability,
  // otherwise 0..max_gap_m wide.
  double max_gap_m = 0.003;
  double zero_gap_probability = 0.5;
  /// Touching rows: bricks end to end up to this row length (at least one).
  double max_row_length_m = 2.0;
  /// Pallet footprint (a EUR pallet by default).
  double pallet_length_m = 1.2;
  double pallet_width_m = 0.8;
  double missing_box_probability = 0.08;
  /// Largest horizontal shift of a stacked pallet layer.
  double layer_offset_m = 0.05;
  /// Table boxes.
  int max_table_boxes = 4;
  /// Chance that a table box stands on a side or an end instead of lying flat.
  double upright_probability = 0.7;
  /// Chance that a table box is put on top of an earlier one.
  double stack_probability = 0.3;
  /// Radius of the rounded top edges (Scene::edge_radius_m); the box kinds
  /// default to 4 mm, the brick kinds to sharp edges.
  double edge_radius_m = 0.0;
  /// Types without a plate colour are painted as cardboard with tape,
  /// printed labels and barcodes (false: plain colour).
  bool markings = true;

  /// The defaults of `kind`: distances and view angles that frame its piles
  /// (pallets from 1.2-2 m above, table boxes obliquely 30-70 deg from the
  /// vertical), and its layer and row counts.
  static SceneParams defaultsFor(SceneKind kind);

  /// Named view angles: "top" (elevation 65-89 deg) or "oblique" (20-60 deg
  /// above the horizon, i.e. 30-70 deg from the vertical). Throws ConfigError
  /// naming parameter 'view' otherwise.
  void applyView(const std::string& view);

  /// Throws ConfigError naming the offending field.
  void validate(const BrickCatalogue& catalogue) const;
};

class SceneGenerator
{
public:
  /// Throws ConfigError on unknown types or bad ranges.
  SceneGenerator(BrickCatalogue catalogue, SceneParams params);

  Scene generate(std::uint64_t seed) const;

  const SceneParams& params() const { return params_; }

private:
  BrickCatalogue catalogue_;
  SceneParams params_;
};

/// Places the camera at `distance_m` from `target_world`, looking at it from
/// `elevation_deg` above the horizon and `azimuth_deg` around the vertical.
Eigen::Isometry3d lookAt(const Eigen::Vector3d& target_world, double distance_m, double elevation_deg,
                         double azimuth_deg);
}  // namespace sim
}  // namespace brick_pose
