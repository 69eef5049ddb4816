#pragma once
// Colour segmentation of the plates (paper, "RGB based segmentation"): an
// HSV box per brick type, morphological clean-up and connected components.
// Works on the image only, so no 3D is built for background pixels.
//
// For speed the colours are first searched on an image subsampled by
// `coarse_factor`; only the (padded) boxes of the coarse blobs are then
// segmented at full resolution. Plates of one colour that touch in the image
// but lie at different depths (stacked layers of a pile) are cut apart where
// the aligned depth jumps.

#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct HsvSegmenterParams
{
  /// Components smaller than this are noise (a red plate at 2 m covers ~12000 px).
  int min_area_px = 400;
  /// Side of the square opening kernel (removes speckle); 0 or 1 disables.
  int open_kernel_px = 3;
  /// Side of the square closing kernel (fills pinholes from glare); 0 or 1
  /// disables. Kept small: a larger one bridges the 1-3 cm gaps between the
  /// plates of a pile seen from 2 m.
  int close_kernel_px = 3;
  /// Subsampling of the coarse colour search (1 = search at full resolution).
  int coarse_factor = 2;
  /// Neighbouring mask pixels whose depths differ by more than this belong to
  /// different plates (bricks are 0.2 m tall; D415 noise at 2 m is ~7 mm).
  /// 0 disables the cut.
  double depth_jump_m = 0.06;
  /// The colours are searched on this many threads (1: in the caller's).
  /// Each type's search is independent, and on a pile the colours' boxes
  /// cost about the same, so two threads about halve the segmentation. Not
  /// a parameter of its own: the front end passes front_end_threads.
  int worker_threads = 1;

  void validate() const;  ///< Throws ConfigError naming the field.
};

class HsvSegmenter
{
public:
  explicit HsvSegmenter(const HsvSegmenterParams& params = HsvSegmenterParams());

  /// One segment per connected component of each type's colour, largest
  /// first within a type; types in catalogue order.
  std::vector<Segment> segment(const RgbdFrame& frame, const BrickCatalogue& catalogue) const;

  /// Binary mask (CV_8UC1, 0/255) of the pixels of an HSV image (OpenCV
  /// units) inside `range`; handles hue ranges that wrap through 0.
  static cv::Mat thresholdHsv(const cv::Mat& hsv, const HsvRange& range);

  /// Removes speckle and fills pinholes of a binary mask in place.
  void cleanMask(cv::Mat& mask) const;

  /// Clears the mask pixels that have a 4-neighbour in the mask across a
  /// depth jump larger than depth_jump_m (`depth_m` covers the same pixels).
  void cutAtDepthJumps(cv::Mat& mask, const cv::Mat& depth_m) const;

  /// Connected components of a clean mask above the minimum area, as
  /// segments of type `type_name` (pixel indices only where depth exists).
  /// `mask` covers `roi_px` of an image `image_width_px` wide and `depth_m`
  /// is the full depth image.
  std::vector<Segment> components(const cv::Mat& mask, const cv::Mat& depth_m, const std::string& type_name,
                                  const cv::Rect& roi_px, int image_width_px) const;

  const HsvSegmenterParams& params() const { return params_; }

private:
  /// Full-resolution boxes (padded, merged where they overlap) around the
  /// blobs of `range` in the coarse HSV image.
  std::vector<cv::Rect> coarseBoxes(const cv::Mat& coarse_hsv, const HsvRange& range, cv::Size image_size) const;

  HsvSegmenterParams params_;
};
}  // namespace brick_pose
