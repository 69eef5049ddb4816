#pragma once
// Everything that configures the synthetic rig, read from named string
// parameters. The SyntheticCamera nodelet feeds it from rosparam and the
// brick_pose_simulate tool from its command line, so both accept the same
// names and give the same errors.

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "brick_pose/camera/pinhole_camera.h"
#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/param_parsing.h"
#include "brick_pose/sim/scene_generator.h"
#include "brick_pose/sim/sensor_model.h"

namespace brick_pose
{
namespace sim
{
struct RigConfig
{
  BrickCatalogue catalogue = BrickCatalogue::mbzirc2020();
  PinholeCamera camera = PinholeCamera::d415Color1280x720();
  SensorModel sensor;
  SceneParams scene;
  std::uint64_t seed = 1;
};

using brick_pose::ParamLookup;

/// Names understood by rigConfigFrom(), with their meaning (for --help).
const std::vector<std::pair<std::string, std::string>>& rigParameterHelp();

/// Builds and validates a RigConfig. Unset parameters keep their defaults.
/// Throws ConfigError naming the parameter on a bad value.
RigConfig rigConfigFrom(const ParamLookup& lookup);
}  // namespace sim
}  // namespace brick_pose
