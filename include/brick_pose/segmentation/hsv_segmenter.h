#pragma once
// Colour segmentation of the plates (paper, "RGB based segmentation"): an
// HSV box per brick type, morphological clean-up and connected components.
// Works on the image only, so no 3D is built for background pixels.

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
  /// Side of the square closing kernel (fills pinholes from glare); 0 or 1 disables.
  int close_kernel_px = 5;

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

  /// Connected components of a clean mask above the minimum area, as
  /// segments of type `type_name` (pixel indices only where depth exists).
  std::vector<Segment> components(const cv::Mat& mask, const cv::Mat& depth_m,
                                  const std::string& type_name) const;

  const HsvSegmenterParams& params() const { return params_; }

private:
  HsvSegmenterParams params_;
};
}  // namespace brick_pose
