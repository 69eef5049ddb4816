#pragma once
// Whether a face is of one plain colour: a plate, an unprinted brick. On such
// a face a dark line where touching faces meet is their seam (the rounded
// edges turn from the light), while on a printed box lines are everywhere
// (tape, labels, barcodes) and say nothing. Colour-free segmentation has no
// colour to find a plate by, so this is measured on the face itself.

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"

namespace brick_pose
{
struct ColourUniformityParams
{
  /// The face's rim is left out (px): its edges, seams and the colour's
  /// 1-2 px misregistration against the depth that drew the mask.
  int rim_px = 4;
  /// A pixel is off the face's colour when its grey level is this many
  /// robust standard deviations of the face's own scatter from the median,
  /// and at least min_contrast levels (sensor noise, low light included,
  /// stays within both)...
  double outlier_sigmas = 5.0;
  double min_contrast = 24.0;
  /// ... and a face with more than this share of such pixels is not plain
  /// (a label, a tape stripe or a barcode covers more).
  double max_outlier_fraction = 0.02;
  /// A plain face's own grey scatter (robust standard deviation) stays
  /// below this: sensor noise is 1-5 levels on the rig (low light
  /// included), while printed boxes scatter by 13-60 (real mOSD boxes).
  double max_sigma_grey = 10.0;
  /// Pixels read at most (every k-th row and column beyond).
  int max_samples = 4000;
};

struct ColourUniformity
{
  double median_grey = 0.0;
  double sigma_grey = 0.0;        ///< Robust (1.4826 MAD).
  double outlier_fraction = 1.0;  ///< Of the pixels read.
  int samples = 0;
  bool uniform = false;           ///< Enough samples, a small scatter and few outliers.
};

/// The colour uniformity of the pixels of `mask` (CV_8UC1, non-zero inside)
/// placed at `box` in `frame`.
ColourUniformity measureColourUniformity(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box,
                                         const ColourUniformityParams& params = ColourUniformityParams());
}  // namespace brick_pose
