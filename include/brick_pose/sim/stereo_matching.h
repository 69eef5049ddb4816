#pragma once
// What a D4xx's stereo matcher makes of the true depth, before its noise:
// the matching window sees a few pixels around each pixel, so
//  - surfaces whose disparities differ by less than kBlendDisparityPx are
//    matched together and averaged (seams, narrow gaps, creases and small
//    steps are smoothed over: two touching boxes show no gap, only a faint
//    crease);
//  - at larger steps the foreground's texture wins the window: the nearer
//    surface grows by `fattening_px` pixels into the farther one (a gap
//    narrower than twice that closes).
// Planes keep their depth exactly: disparity is affine in the image over a
// plane and a symmetric window's mean of an affine function is its centre
// value, so only pixels near a surface boundary are processed.

#include <opencv2/core.hpp>

namespace brick_pose
{
namespace sim
{
/// Disparity difference (pixels) below which two surfaces in one window are
/// averaged rather than one winning.
constexpr double kBlendDisparityPx = 0.5;

struct StereoWindow
{
  int window_px = 1;     ///< odd side of the matching window; 1 = no smoothing
  int fattening_px = 0;  ///< foreground growth at depth steps
  double focal_baseline_px_m = 50.6;  ///< fx * baseline: disparity = this / depth
};

/// `depth_m`: CV_32FC1 true depth, NaN where nothing. `boundaries`: CV_8UC1,
/// non-zero on pixels next to another surface or on a curved part of one
/// (the only places the window changes anything). Returns the depth the
/// matcher reports, NaN where it has none.
cv::Mat stereoMatchedDepth(const cv::Mat& depth_m, const cv::Mat& boundaries, const StereoWindow& window);
}  // namespace sim
}  // namespace brick_pose
