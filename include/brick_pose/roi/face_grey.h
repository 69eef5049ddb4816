#pragma once
// The grey level a face's seams and edge lines are read in: each pixel's
// channels weighted by the face's own mean colour.
//
// A seam between two touching faces is shading: it darkens each channel in
// proportion to what the face reflects there. Weighting the channels by the
// face's colour is the matched filter for such a line. On a grey face the
// weights are equal, the plain mean of the three channels. On a saturated
// face (a red plate) the channels the face barely reflects add only noise,
// and the plain mean would read the seam at a third of its contrast with
// 0.58 of the noise: in low light the seams between touching red bricks,
// plain to the eye in the red channel, were lost in that noise.
#include <array>
#include <opencv2/core.hpp>

namespace brick_pose
{
/// Pixels whose depth lies this close to a face's plane give the colour its
/// grey is weighted by: the face, or a neighbour on its plane (depth noise
/// at 2 m is a few millimetres; a step to the ground is far more).
constexpr double kFaceColourOnPlaneM = 0.01;

class FaceGrey
{
public:
  /// Equal weights: the mean of the three channels.
  FaceGrey() = default;

  /// Weights in proportion to `mean_bgr` (the face's mean colour, grey
  /// levels); equal weights when the face is black.
  static FaceGrey ofColour(const cv::Vec3d& mean_bgr)
  {
    FaceGrey grey;
    const double sum = mean_bgr[0] + mean_bgr[1] + mean_bgr[2];
    // Below a grey level in all three there is no colour to weight by.
    if (!(sum >= 3.0)) return grey;
    for (int c = 0; c < 3; ++c) grey.weights_[c] = mean_bgr[c] / sum;
    return grey;
  }

  /// The grey level of a pixel (or of a mean colour, with fractional
  /// levels): the weighted sum (weights add up to one, so a grey pixel reads
  /// its own level).
  template <typename Level>
  double operator()(const cv::Vec<Level, 3>& bgr) const
  {
    return weights_[0] * bgr[0] + weights_[1] * bgr[1] + weights_[2] * bgr[2];
  }

  const std::array<double, 3>& weights() const { return weights_; }

private:
  std::array<double, 3> weights_{{1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0}};
};

/// Sums the colour of the pixels that lie on a face, for FaceGrey::ofColour.
class FaceColourSum
{
public:
  void add(const cv::Vec3b& bgr)
  {
    for (int c = 0; c < 3; ++c) sum_[c] += bgr[c];
    ++count_;
  }
  /// The face's grey: equal weights when no pixel was added.
  FaceGrey grey() const { return count_ == 0 ? FaceGrey() : FaceGrey::ofColour(mean()); }
  /// The mean colour (BGR grey levels); black when no pixel was added.
  cv::Vec3d mean() const { return count_ == 0 ? cv::Vec3d(0.0, 0.0, 0.0) : sum_ / static_cast<double>(count_); }

private:
  cv::Vec3d sum_{0.0, 0.0, 0.0};
  long count_ = 0;
};
}  // namespace brick_pose
