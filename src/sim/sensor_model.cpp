#include "brick_pose/sim/sensor_model.h"

#include <cmath>
#include <cstdlib>

#include "brick_pose/common/enum_names.h"
#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace sim
{
constexpr EnumName<Lighting> kLightingNames[] = {
    {Lighting::kNormal, "normal"}, {Lighting::kSunlight, "sunlight"}, {Lighting::kLowLight, "low_light"}};

constexpr EnumName<DepthModel> kDepthModelNames[] = {{DepthModel::kIdeal, "ideal"}, {DepthModel::kD4xx, "d4xx"}};

Lighting lightingFromString(const std::string& name)
{
  return parseEnumName("parameter 'lighting'", name, kLightingNames);
}

std::string toString(Lighting lighting) { return enumName(lighting, kLightingNames); }

DepthModel depthModelFromString(const std::string& name)
{
  return parseEnumName("parameter 'depth_model'", name, kDepthModelNames);
}

std::string toString(DepthModel model) { return enumName(model, kDepthModelNames); }

SensorModel SensorModel::d4xx()
{
  SensorModel sensor;
  // The D4xx census window is 7x7 at the depth imager's resolution; its
  // foreground fattening is a few pixels; its subpixel disparity comes in
  // 1/32 px steps (Intel's subpixel linearity white paper); aligned depth
  // is commonly 1-2 px off the colour image.
  sensor.stereo_window_px = 7;
  sensor.edge_fattening_px = 3;
  sensor.disparity_step_px = 1.0 / 32.0;
  sensor.depth_offset_u_px = 2;
  sensor.depth_offset_v_px = 1;
  return sensor;
}

double SensorModel::quantisedDepth(double depth_m, double fx_px) const
{
  if (disparity_step_px <= 0.0 || !(depth_m > 0.0)) return depth_m;
  const double focal_baseline = fx_px * baseline_m;
  const double steps = std::round(focal_baseline / depth_m / disparity_step_px);
  // A disparity that rounds to zero is infinitely far: no depth.
  return steps > 0.0 ? focal_baseline / (steps * disparity_step_px) : 0.0;
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
  check(stereo_window_px >= 1 && stereo_window_px <= 31 && stereo_window_px % 2 == 1,
        "parameter 'stereo_window_px' must be odd, in 1..31");
  check(edge_fattening_px >= 0 && edge_fattening_px <= 15, "parameter 'edge_fattening_px' must be in 0..15");
  check(disparity_step_px >= 0.0 && disparity_step_px <= 1.0, "parameter 'disparity_step_px' must be in [0, 1]");
  check(std::abs(depth_offset_u_px) <= 16, "parameter 'depth_offset_u_px' must be in -16..16");
  check(std::abs(depth_offset_v_px) <= 16, "parameter 'depth_offset_v_px' must be in -16..16");
}
}  // namespace sim
}  // namespace brick_pose
