#pragma once
// Axial depth noise of a triangulating sensor (active stereo, structured
// light): sigma(z) = coefficient * z^2, with a floor for what no sensor
// model covers (surfaces that are not quite flat, quantisation).
//
// The coefficient differs by sensor and by resolution (a D415 at 640x480 has
// half the focal length, so twice the noise of 1280x720), so the colour-free
// segmenter measures it on every frame from the residuals of its planar
// pixel blocks, within configured bounds.

#include <vector>

#include "brick_pose/segmentation/plane_moments.h"

namespace brick_pose
{
struct DepthNoise
{
  double sigma_at_1m_m = 0.0016;
  double floor_m = 0.0005;
  /// Stereo and structured-light depth noise is correlated over the matching
  /// window: a patch's mean does not average out its pixels' noise. Points
  /// within about this many pixels count as one independent sample.
  double correlated_points = 64.0;

  /// Independent noise samples among `count` points (at least one).
  double samples(double count) const { return count > correlated_points ? count / correlated_points : 1.0; }

  double sigma(double depth_m) const
  {
    const double sigma_m = sigma_at_1m_m * depth_m * depth_m;
    return sigma_m > floor_m ? sigma_m : floor_m;
  }

  /// Expected squared distance of a set's points to their true plane: the
  /// mean of sigma(z)^2 over the set (approximated as the sum of the
  /// z^2-law part and the floor).
  double variance(const PlaneMoments& moments) const
  {
    return sigma_at_1m_m * sigma_at_1m_m * moments.z4 / moments.count + floor_m * floor_m;
  }
};

/// The coefficient a such that blocks' plane-fit residuals are a z^2: the
/// `quantile` of sqrt(mse / z^4) over the blocks, clamped to [min, max].
/// Non-planar blocks (edges, clutter) only raise the upper quantiles, so a
/// low quantile reads the noise of the flat majority. Returns `fallback`
/// when there are no blocks.
double estimateNoiseAt1m(std::vector<double> normalised_mse, double quantile, double min_at_1m_m,
                         double max_at_1m_m, double fallback_at_1m_m);
}  // namespace brick_pose
