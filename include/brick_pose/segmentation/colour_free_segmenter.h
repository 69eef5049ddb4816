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

#include <optional>
#include <vector>

#include <Eigen/Core>
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
  /// Side of the square pixel blocks that are clustered; 0 makes it the
  /// image width / cells_across (8 px at 640, 16 px at 1280), so a face
  /// spans as many cells at any resolution. Smaller finds smaller faces (a
  /// face needs min_plane_cells whole cells) and costs more.
  int cell_px = 0;
  double cells_across = 80.0;
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
  /// Up to this many pixels without a plane between two pixels of one
  /// region in a row (dropouts, outliers) belong to the region's mask.
  int max_gap_px = 2;
  /// Split the per-pixel passes over OpenCV's threads.
  bool parallel = true;
  /// The supporting plane (ground, table) is the largest region covering at
  /// least this fraction of the image with no other region more than
  /// support_margin_m below it and some region more than that above it.
  double support_min_image_fraction = 0.1;
  double support_margin_m = 0.03;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// Time of the stages of one call, milliseconds: wall, and CPU of the
/// calling thread (work split onto OpenCV's other threads not included).
struct ColourFreeTimings
{
  double cells_ms = 0.0;       ///< Cell moments and planes, noise estimate.
  double clustering_ms = 0.0;  ///< Agglomerative clustering and plane grouping.
  double refinement_ms = 0.0;  ///< Pixel labels, regions joined at pixel level.
  double segments_ms = 0.0;    ///< Masks, components, pixel lists, supporting plane.
  double cells_cpu_ms = 0.0, clustering_cpu_ms = 0.0, refinement_cpu_ms = 0.0, segments_cpu_ms = 0.0;
  double noise_at_1m_m = 0.0;  ///< The noise coefficient used.
  int planes = 0;              ///< Planes found on the cells.
  int regions = 0;             ///< Regions they form, before the area threshold.
  int seeded_cells = 0;        ///< Cells inside a given support, clustered as one node from the start.
};

/// Segments with their planes and which of them are the supporting plane.
struct PlanarSegments
{
  std::vector<Segment> segments;     ///< Largest first.
  std::vector<MomentPlane> planes;   ///< Plane of each segment's region (from its cells).
  /// Per segment: part of the plane everything else stands on (the ground or
  /// a table: no region lies below it, some lie above it). A planar region
  /// of touching boxes with nothing on it is not supporting; the lower layer
  /// of a stack seen without the ground is.
  std::vector<bool> supporting;
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

  /// The same segments with their planes and the supporting plane marked;
  /// without `with_supporting`, the supporting plane's segments are left
  /// out (not built: they are most of the image).
  ///
  /// With `given_support` (n and d: n . x + d is, for a unit n, the height
  /// of camera point x above the plane the pile stands on, as tf gives it;
  /// InputError when it is not finite or n is zero), the supporting plane
  /// is the regions lying on it (within support_margin_m, parallel within
  /// the clustering's min_angle_deg) and no other: a layer's top filling a
  /// close view, with a lower one beside it, is never taken for the support.
  /// The cells inside it start the clustering as one node
  /// (CellClustering::cluster's seeds; timings->seeded_cells).
  ///
  /// Without a given support, a `likely_plane` (the same form; e.g. the
  /// dominant plane a quick RANSAC found) only seeds the clustering so: it
  /// makes it faster where much of the view lies on it, and decides nothing
  /// (the supporting plane is then found as without it).
  PlanarSegments segmentPlanes(const RgbdFrame& frame, const cv::Mat& excluded = cv::Mat(),
                               ColourFreeTimings* timings = nullptr, bool with_supporting = true,
                               const std::optional<Eigen::Vector4d>& given_support = std::nullopt,
                               const std::optional<Eigen::Vector4d>& likely_plane = std::nullopt) const;

  /// The planar region of each pixel (CV_32SC1, -1 none) before the
  /// regions are cut into connected segments, for tests and tools.
  cv::Mat labelRegions(const RgbdFrame& frame, const cv::Mat& excluded = cv::Mat(),
                       ColourFreeTimings* timings = nullptr) const;

  const ColourFreeParams& params() const { return params_; }

  /// The cell size used for an image `width_px` wide.
  int cellPx(int width_px) const;

private:
  double measuredNoiseAt1m(const CellGrid& grid) const;
  /// Plane index per pixel (-1 none) into `labels`; returns the planes
  /// and their regions.
  /// With `seeded` (a unit-normal plane), its inside starts the clustering
  /// as one node (innerSupportCells).
  CellPlanes labelPlanes(const RgbdFrame& frame, const cv::Mat& excluded, cv::Mat& labels,
                         ColourFreeTimings& timings,
                         const std::optional<Eigen::Vector4d>& seeded = std::nullopt) const;
  /// Per cell, 1 for those inside the unit-normal plane `support` (n . x +
  /// d): they and their eight neighbours lie on it (nodes by
  /// CellClustering::planarCell, within support_margin_m of it, flat about
  /// its normal, and on one plane: onOnePlane). The clustering starts them
  /// as one node.
  std::vector<std::uint8_t> innerSupportCells(const CellGrid& grid, const std::vector<MomentPlane>& cell_planes,
                                              const DepthNoise& noise, const Eigen::Vector4d& support) const;
  /// Of the cells non-zero in `near` (near `support`), those within the
  /// `noise` of the plane of those at their median height above it.
  static std::vector<std::uint8_t> onOnePlane(const CellGrid& grid, const std::vector<std::uint8_t>& near,
                                              const Eigen::Vector4d& support, const DepthNoise& noise);
  /// The cells of `cells` (cols x rows, row-major) whose eight neighbours
  /// in the grid are in it too.
  static std::vector<std::uint8_t> insideOf(const std::vector<std::uint8_t>& cells, int cols, int rows);
  /// Whether the region of `plane` and `area_px` (> 0) lies on the
  /// unit-normal plane `support` (n . x + d): within support_margin_m of it
  /// and parallel within min_angle_deg. A given support, or the one found.
  bool onSupport(const MomentPlane& plane, int area_px, const Eigen::Vector4d& support) const;
  /// Per region: whether it is the supporting plane (see PlanarSegments).
  std::vector<bool> supportingRegions(const std::vector<MomentPlane>& planes, const std::vector<int>& area_px,
                                      int image_area_px) const;

  ColourFreeParams params_;
  CellClustering clustering_;
};
}  // namespace brick_pose
