#include "brick_pose/sim/sensor_model.h"

#include <cmath>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace sim
{
Lighting lightingFromString(const std::string& name)
{
  if (name == "normal") return Lighting::kNormal;
  if (name == "sunlight") return Lighting::kSunlight;
  if (name == "low_light") return Lighting::kLowLight;
  throw ConfigError("lighting: unknown mode '" + name + "' (expected normal, sunlight or low_light)");
}

std::string toString(Lighting lighting)
{
  switch (lighting)
  {
    case Lighting::kSunlight:
      return "sunlight";
    case Lighting::kLowLight:
      return "low_light";
    case Lighting::kNormal:
    default:
      return "normal";
  }
}

void SensorModel::validate() const
{
  auto check = [](bool ok, const std::string& message) {
    if (!ok) throw ConfigError("sensor model: " + message);
  };
  check(baseline_m > 0.0 && std::isfinite(baseline_m), "baseline_m must be > 0");
  check(subpixel_px >= 0.0 && std::isfinite(subpixel_px), "subpixel_px must be >= 0");
  check(min_depth_m >= 0.0 && max_depth_m > min_depth_m, "need 0 <= min_depth_m < max_depth_m");
  auto probability = [&](double p, const char* name) {
    check(p >= 0.0 && p <= 1.0, std::string(name) + " must be in [0, 1]");
  };
  probability(flying_pixel_probability, "flying_pixel_probability");
  probability(dropout_probability, "dropout_probability");
  check(grazing_cos >= 0.0 && grazing_cos < 1.0, "grazing_cos must be in [0, 1)");
  check(depth_edge_threshold_m > 0.0, "depth_edge_threshold_m must be > 0");
  check(colour_noise_sigma >= 0.0, "colour_noise_sigma must be >= 0");
}
}  // namespace sim
}  // namespace brick_pose
