#pragma once
// Agglomerative hierarchical clustering of planar cells (after PEAC, Feng,
// Taguchi and Kamat, ICRA 2014), our own formulation:
//
//  - a cell is a node when its points fit a plane within the depth noise;
//  - the node with the smallest plane-fit MSE is taken from a min-heap and
//    absorbs its compatible neighbours, the one giving the smallest merged
//    MSE first (PEAC merges only that one per step; taking all of them, each
//    re-tested against the grown node, keeps large planes from rescanning
//    their border once per cell); a node with no compatible neighbour
//    retires, as a plane when it spans enough cells, but may still be
//    absorbed by a neighbour that grows up to it later;
//  - finally adjacent planes that continue each other are grouped: a large
//    surface that is not quite flat (a table seen by a Kinect bends by
//    centimetres) leaves the clustering as several planes; they form one
//    region when they are compatible as above, or when their normals agree
//    and the cells along their seam lie on one surface (no step). Each plane keeps its own equation for the pixel
//    refinement; the region is the union of its planes' pixels.
//
// "Compatible" is judged against the noise expected at the points' depth,
// so the same thresholds hold at 0.5 m and at 3 m, for a D415 and a Kinect:
// the smaller node must lie along the larger one's plane (angle within what
// the two normals' uncertainties allow), its points must scatter about that
// plane no more than the noise does, its centroid must be on it within the
// centroid's uncertainty, and the merged set must still be a plane. The MSE
// alone would let a small node 2 cm off a large plane merge: it hardly
// raises the large node's MSE.

#include <cstdint>
#include <vector>

#include "brick_pose/segmentation/cell_grid.h"
#include "brick_pose/segmentation/depth_noise.h"
#include "brick_pose/segmentation/plane_moments.h"

namespace brick_pose
{
struct CellClusteringParams
{
  /// A cell takes part when this fraction of a full cell's pixels has depth.
  double min_cell_fill = 0.75;
  /// A cell is planar when its plane-fit MSE is within this many noise sigmas (squared).
  double cell_sigma_factor = 2.0;
  /// Scatter of the smaller node about the larger node's plane, in noise sigmas.
  double spread_sigma_factor = 2.0;
  /// Offset of the smaller node's centroid from the larger node's plane, in
  /// sigmas of that offset's uncertainty, plus offset_floor_m.
  double offset_sigma_factor = 3.0;
  double offset_floor_m = 0.002;
  /// MSE of a merged node, in noise sigmas, plus plane_floor_m for surfaces
  /// that are flat only to a millimetre (cardboard, a table).
  double merge_sigma_factor = 2.0;
  double plane_floor_m = 0.001;
  /// Angle between the two normals: min_angle_deg plus angle_sigma_factor
  /// times their combined uncertainty, at most max_angle_deg.
  /// The floor is generous: cuboid faces meet at 90 degrees, and a small
  /// node's normal scatters more than its nominal uncertainty says (the
  /// nodes left over are the outliers among thousands of tests).
  double min_angle_deg = 10.0;
  double angle_sigma_factor = 3.0;
  double max_angle_deg = 45.0;
  /// Nodes retired with fewer cells are not planes (their pixels stay free
  /// for the pixel-level refinement of their neighbours).
  int min_plane_cells = 3;
  /// ... or whose normal is less certain than this (one sigma).
  double max_plane_normal_sigma_deg = 10.0;
  /// Cells seen more obliquely than this are not planar cells: the points
  /// of a cell of noise or of a depth edge spread along the viewing rays and
  /// fit a plane containing them.
  double max_incidence_deg = 84.0;
  /// A cell whose largest pixel-to-pixel depth step exceeds the step its
  /// plane predicts by more than this many sigmas (of a difference of two
  /// pixels), and by more than min_step_fraction of the depth, spans a depth
  /// edge. The fraction keeps a noise model that is a little low (the noise
  /// is not exactly proportional to z^2) from breaking up flat faces; a
  /// largest step is the tail of ~100 differences.
  double step_sigma_factor = 4.0;
  double min_step_fraction = 0.01;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// A node of the clustering: points, their plane and the statistics the
/// merge tests read, computed once per change of the node.
struct PlaneNode
{
  PlaneMoments moments;
  MomentPlane plane;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  double noise_variance_m2 = 0.0;  ///< Expected squared residual at the points' depths.
  double normal_sigma_rad = 0.0;   ///< Uncertainty of the plane's normal.

  PlaneNode() = default;
  /// Statistics of `moments` whose plane is `plane` (fitted from them).
  PlaneNode(const PlaneMoments& moments, const MomentPlane& plane, const DepthNoise& noise);
};

/// The plane of each cell with enough pixels (invalid otherwise); with
/// `parallel`, split over OpenCV's threads.
std::vector<MomentPlane> fitCellPlanes(const CellGrid& grid, double min_cell_fill, bool parallel = false);

/// Where two planes meet: the points on either side of their seam.
struct PlaneSeam
{
  int first = 0, second = 0;  ///< Plane indices, first < second.
  int length = 0;             ///< Neighbouring cell or pixel pairs along it.
  PlaneMoments first_side, second_side;
};

/// Result of the clustering: planes and the plane of each cell.
struct CellPlanes
{
  std::vector<int> cell_labels;  ///< Per cell: index into `planes`, or -1.
  std::vector<MomentPlane> planes;
  std::vector<PlaneMoments> moments;
  std::vector<int> cell_counts;  ///< Cells per plane.
  /// Region of each plane (0 .. region_count - 1): planes that continue
  /// each other share one.
  std::vector<int> regions;
  int region_count = 0;
};

class CellClustering
{
public:
  /// Throws ConfigError for a bad parameter.
  explicit CellClustering(const CellClusteringParams& params);

  /// Clusters the cells of `grid` whose plane (`cell_planes`, from
  /// fitCellPlanes) is valid and flat within `noise`.
  ///
  /// Cells non-zero in `seeds` (empty, or one per cell) known to lie on one
  /// surface, e.g. the inside of a given support, start merged: each
  /// 4-connected group of them that are nodes starts as one node when every
  /// one of its cells liesOn() it (else they start alone), and
  /// the clustering grows it from there as it grows any node. On a pile
  /// seen from above the ground is most of the cells, and merging it cell
  /// by cell was most of the clustering's time. Returns in `seeded` (when
  /// given) how many cells started merged.
  CellPlanes cluster(const CellGrid& grid, const std::vector<MomentPlane>& cell_planes, const DepthNoise& noise,
                     const std::vector<std::uint8_t>& seeds = {}, int* seeded = nullptr) const;

  /// Whether a cell is a node: its plane is valid, seen less obliquely than
  /// max_incidence_deg, flat within the noise and without a depth step.
  bool planarCell(const CellGrid& grid, int cell, const MomentPlane& plane, const DepthNoise& noise) const;

  /// Whether the cell's largest pixel-to-pixel depth step is more than a
  /// surface along `plane` explains (the cell spans a depth edge).
  bool depthStep(const CellGrid& grid, int cell, const MomentPlane& plane, const DepthNoise& noise) const;

  /// Whether the nodes `a` and `b` may merge (see the file comment). On
  /// success `merged_mse_m2` receives an upper bound of the merged MSE (the
  /// MSE of the union about the larger node's plane).
  bool compatible(const PlaneNode& a, const PlaneNode& b, const DepthNoise& noise, double& merged_mse_m2) const;

  /// Whether the points of `small` lie on the plane of `large` within the
  /// noise: compatible()'s scatter and offset tests, without its test of
  /// the angle between their normals (a single cell's normal far away is
  /// mostly noise).
  bool liesOn(const PlaneNode& large, const PlaneNode& small, const DepthNoise& noise) const;

  /// Whether planes p and q continue each other across their seam, given
  /// the moments of the seam cells on either side (see the file comment).
  bool continuous(const PlaneNode& p, const PlaneMoments& p_seam, const PlaneNode& q, const PlaneMoments& q_seam,
                  const DepthNoise& noise) const;

  /// Joins the regions of planes whose pixels touch along at least
  /// `min_length` pixel pairs (seams from planeBorders()) where they
  /// continue each other or are compatible: pixel refinement grows planes
  /// through cells that did not cluster (noise, dropouts), so two pieces of
  /// one face may meet only at pixel level.
  void joinTouchingRegions(const std::vector<PlaneSeam>& seams, int min_length, const DepthNoise& noise,
                           CellPlanes& planes) const;

  const CellClusteringParams& params() const { return params_; }

private:
  /// Largest angle between two normals whose combined uncertainty is `normal_sigma_rad`.
  double maxAngleRad(double normal_sigma_rad) const;
  /// compatible()'s scatter of `small` about the plane of `large` and its
  /// offset from it; whether both are within the noise.
  bool withinNoise(const PlaneNode& large, const PlaneNode& small, const DepthNoise& noise, double& spread_m2,
                   double& offset_m) const;
  /// Groups planes that continue each other into regions.
  void groupContinuousPlanes(const CellGrid& grid, const DepthNoise& noise, CellPlanes& result) const;

  CellClusteringParams params_;
};
}  // namespace brick_pose
