#pragma once
// Seeded scenes for the synthetic rig: single bricks, organised piles (rows
// and stacked layers) and unorganised piles (bricks dropped onto each other).

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
};

/// "single", "organised_pile", "unorganised_pile"; throws ConfigError otherwise.
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
  int max_rows = 3;         // organised piles
  int max_layers = 2;

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
