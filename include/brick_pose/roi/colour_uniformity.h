#pragma once
// Whether a face is of one plain colour: a plate, an unprinted brick. On such
// a face a dark line where touching faces meet is their seam (the rounded
// edges turn from the light), while on a printed box lines are everywhere
// (tape, labels, barcodes) and say nothing. Colour-free segmentation has no
// colour to find a plate by, so this is measured on the face itself.

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/face_grey.h"

namespace brick_pose
{
struct ColourUniformityParams
{
  /// The face's rim is left out (px): its edges, seams and the colour's
  /// 1-2 px misregistration against the depth that drew the mask.
  int rim_px = 4;
  /// The face is read in blocks of this many pixels square (their mean
  /// grey): averaging quarters the pixel noise, so that print still stands
  /// out in low light, where a label is 20 grey levels above dark cardboard
  /// and the pixel noise 6.
  int block_px = 4;
  /// A block is off the face's colour when its grey level is this many
  /// robust standard deviations of the blocks' scatter from their median,
  /// and at least min_contrast levels...
  double outlier_sigmas = 5.0;
  double min_contrast = 8.0;
  /// ... and a face with more than this share of such blocks is not plain
  /// (a label, a tape stripe or a barcode covers more).
  double max_outlier_fraction = 0.02;
  /// A plain face's blocks scatter less than this (robust standard
  /// deviation, grey levels): sensor noise leaves 1-2 on the rig, low light
  /// included, while printed boxes scatter by 10-60 (real mOSD boxes).
  double max_sigma_grey = 8.0;
  /// Blocks read at most (every k-th block row and column beyond).
  int max_samples = 4000;
};

struct ColourUniformity
{
  double median_grey = 0.0;
  double sigma_grey = 0.0;        ///< Of the blocks' means, robust (1.4826 MAD).
  double outlier_fraction = 1.0;  ///< Of the blocks read.
  int samples = 0;                ///< Blocks read.
  bool uniform = false;           ///< Enough samples, a small scatter and few outliers.
};

/// `mask` (CV_8UC1) without its rim: the pixels `rim_px` or more inside it
/// (outside the mask's box counts as outside). measureColourUniformity reads
/// only these (params.rim_px).
cv::Mat withoutRim(const cv::Mat& mask, int rim_px);

/// The colour uniformity of the pixels of `mask` (CV_8UC1, non-zero inside)
/// placed at `box` in `frame`.
ColourUniformity measureColourUniformity(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box,
                                         const ColourUniformityParams& params = ColourUniformityParams());

/// The mean grey level (0-255, the mean of R, G and B) of the pixels of
/// `mask` placed at `box` in `frame`; 0 when none is in the image. How
/// bright a face is sets how deep a seam across it can be.
double meanGreyLevel(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box);

/// The same pixels' mean level in the grey their seams are read in
/// (FaceGrey: weighted by their own mean colour); 0 when none is in the
/// image. A seam's line scales with this level: on a saturated face it is
/// up to three times the mean grey level.
double faceGreyLevel(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box);

/// The grey those pixels' seams are read in (FaceGrey::ofColour of their
/// mean colour); equal weights when none is in the image.
FaceGrey faceGreyOf(const RgbdFrame& frame, const cv::Mat& mask, const cv::Rect& box);
}  // namespace brick_pose
