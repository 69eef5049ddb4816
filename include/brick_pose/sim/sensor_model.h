#pragma once
// Parameters of the simulated D415: depth noise, holes and lighting.

#include <cstdint>
#include <string>

namespace brick_pose
{
namespace sim
{
enum class Lighting
{
  kNormal,
  kSunlight,  // bright, washed-out colour, more depth dropouts on bright faces
  kLowLight,  // dark, noisy colour
};

/// "normal", "sunlight", "low_light"; throws ConfigError otherwise.
Lighting lightingFromString(const std::string& name);
std::string toString(Lighting lighting);

struct SensorModel
{
  // Axial noise of active stereo: sigma_z = z^2 * subpixel / (f * baseline).
  // With the D415's 55 mm baseline and ~0.08 px subpixel accuracy this is
  // about 1.6 mm at 1 m.
  double baseline_m = 0.055;
  double subpixel_px = 0.08;
  double min_depth_m = 0.3;   // closer than this the D415 reports 0
  double max_depth_m = 10.0;  // farther than this it reports 0
  /// Probability that a pixel on a depth edge takes a depth between the
  /// foreground and the background (the "flying pixels" of stereo matching).
  double flying_pixel_probability = 0.5;
  double depth_edge_threshold_m = 0.03;
  double dropout_probability = 0.002;  // random holes anywhere
  /// Below this |cos| between the surface normal and the ray, matching fails
  /// most of the time (grazing surfaces).
  double grazing_cos = 0.12;
  /// Pixels the right IR imager cannot see get no depth (the left-edge
  /// "shadow" of objects in D4xx depth).
  bool stereo_shadow = true;
  Lighting lighting = Lighting::kNormal;
  double colour_noise_sigma = 2.0;  // grey levels, before the lighting mode scales it

  /// Throws ConfigError naming the offending field.
  void validate() const;

  double axialSigma(double depth_m, double fx_px) const { return depth_m * depth_m * subpixel_px / (fx_px * baseline_m); }
};
}  // namespace sim
}  // namespace brick_pose
