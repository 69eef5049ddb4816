#pragma once
// Colour-free planar segmentation of an organised RGB-D frame, in real time
// on two cores: the depth image is cut into cells of cell_px x cell_px
// pixels, each with its plane moments (cell_grid.h); cells that are planar
// within the depth noise are clustered agglomeratively into planes
// (cell_clustering.h, after PEAC, Feng et al. ICRA 2014); the planes' borders
// are then decided pixel by pixel (plane_refinement.h). The depth noise
// sigma(z) = a z^2 is measured on each frame from the cells' residuals, so
// one set of parameters serves a D415 at 1280x720 or 640x480 and a Kinect.
//
// Output: one Segment per connected planar region, largest first, type_name
// empty. A region may hold several touching faces of one height (the ROI
// stage splits them); faces at different heights or orientations are kept
// apart, with borders accurate to about a pixel.

#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/segmentation/cell_clustering.h"
#include "brick_pose/segmentation/cell_grid.h"
#include "brick_pose/segmentation/plane_refinement.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct ColourFreeParams
{
  /// Side of the square pixel blocks that are clustered. Smaller finds
  /// smaller faces (a face needs min_plane_cells whole cells) and costs more.
  int cell_px = 8;
  /// Depth noise sigma(z) = a z^2: `a` is measured per frame (the
  /// noise_quantile of sqrt(mse) / z^2 over blocks of 4 x 4 cells) within
  /// [min, max], or fixed at noise_at_1m_m when estimate_noise is false.
  bool estimate_noise = true;
  double noise_at_1m_m = 0.0016;
  double min_noise_at_1m_m = 0.0005;
  double max_noise_at_1m_m = 0.02;
  double noise_quantile = 0.5;
  /// Smallest sigma at any depth (quantisation, near range).
  double noise_floor_m = 0.0005;
  /// Depth noise is correlated over about this many pixels (the stereo
  /// matching window): a patch of that size is one independent sample.
  int noise_correlation_px = 8;
  CellClusteringParams clustering;
  PlaneRefinementParams refinement;
  int min_area_px = 400;  ///< Smaller regions are dropped.
  /// Split the per-pixel passes over OpenCV's threads.
  bool parallel = true;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// Wall time of the stages of one call, milliseconds.
struct ColourFreeTimings
{
  double cells_ms = 0.0;       ///< Cell moments and planes, noise estimate.
  double clustering_ms = 0.0;  ///< Agglomerative clustering and plane joining.
  double refinement_ms = 0.0;  ///< Pixel labels.
  double segments_ms = 0.0;    ///< Masks, components, pixel lists.
  double noise_at_1m_m = 0.0;  ///< The noise coefficient used.
  int planes = 0;              ///< Planes found on the cells.
  int regions = 0;             ///< Regions they form, before the area threshold.
};

class ColourFreeSegmenter
{
public:
  /// Throws ConfigError for a bad parameter.
  explicit ColourFreeSegmenter(const ColourFreeParams& params = ColourFreeParams());

  /// Planar segments of `frame`, largest first. Pixels non-zero in
  /// `excluded` (CV_8UC1 of the frame's size, or empty), e.g. those another
  /// segmenter already took, are treated as having no depth. Throws
  /// InputError when `excluded` has the wrong size or type.
  std::vector<Segment> segment(const RgbdFrame& frame, const cv::Mat& excluded = cv::Mat(),
                               ColourFreeTimings* timings = nullptr) const;

  /// The planar region of each pixel (CV_32SC1, -1 none) before the
  /// regions are cut into connected segments, for tests and tools.
  cv::Mat labelRegions(const RgbdFrame& frame, const cv::Mat& excluded = cv::Mat(),
                       ColourFreeTimings* timings = nullptr) const;

  const ColourFreeParams& params() const { return params_; }

private:
  double measuredNoiseAt1m(const CellGrid& grid) const;
  std::vector<Segment> segmentsFromLabels(const RgbdFrame& frame, const cv::Mat& labels) const;

  ColourFreeParams params_;
  CellClustering clustering_;
};
}  // namespace brick_pose
