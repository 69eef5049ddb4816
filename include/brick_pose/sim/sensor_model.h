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

/// Presets of the depth model: `ideal` keeps the earlier rig's depth (noise,
/// holes, flying pixels, stereo shadow) and renders old scenes bit for bit as
/// before; `d4xx` adds what a real D4xx's stereo matcher and its alignment
/// do (see SensorModel::d4xx()).
enum class DepthModel
{
  kIdeal,
  kD4xx,
};

/// "ideal", "d4xx"; throws ConfigError naming parameter 'depth_model' otherwise.
DepthModel depthModelFromString(const std::string& name);
std::string toString(DepthModel model);

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

  // What the stereo matcher and the depth-to-colour alignment add (all off
  // in the ideal model; see stereo_matching.h).
  /// Side of the matching window in pixels (odd; 1 = off): surfaces within
  /// half a pixel of disparity in one window are averaged, so narrow gaps
  /// and seams between touching boxes vanish from depth.
  int stereo_window_px = 1;
  /// Pixels by which the nearer surface grows into the farther one at a
  /// depth step (0 = off).
  int edge_fattening_px = 0;
  /// Disparity is reported in steps of this many pixels (D4xx: 1/32); depth
  /// = f * B / disparity then comes in steps that grow with z^2 (0 = off).
  double disparity_step_px = 0.0;
  /// Misregistration of the aligned depth: depth pixel (u, v) holds what the
  /// colour image shows at (u - offset_u, v - offset_v) (calibration error
  /// of the depth-to-colour extrinsics).
  int depth_offset_u_px = 0;
  int depth_offset_v_px = 0;

  /// The D4xx preset: 7 px matching window, 3 px edge fattening, 1/32 px
  /// disparity steps, depth misregistered by (2, 1) px.
  static SensorModel d4xx();

  /// Throws ConfigError naming the offending field.
  void validate() const;

  double axialSigma(double depth_m, double fx_px) const { return depth_m * depth_m * subpixel_px / (fx_px * baseline_m); }

  /// Depth after disparity quantisation: f * B / (round(f * B / z / step) * step).
  /// Unchanged when disparity_step_px is 0.
  double quantisedDepth(double depth_m, double fx_px) const;
};
}  // namespace sim
}  // namespace brick_pose
