#pragma once
// ROI filtration (paper section "ROI Filtration"): turns one segment into a
// BrickCandidate, or says why it is not one. Plane and OBB come from the 3D
// points; the outline geometry (least-area quad, T1, T2, centre) from the
// mask, lifted to 3D by intersecting pixel rays with the segment's plane,
// which is more accurate than any single depth pixel.

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/cloud/cloud_processor.h"
#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/segmentation/segment.h"

namespace brick_pose
{
struct RoiFilterParams
{
  int min_points = 50;            ///< Segments with fewer depth pixels are dropped.
  /// Larger segments are thinned to about this many pixels (every k-th pixel
  /// in raster order) before 3D: the plane of 10000 points is as good as that
  /// of 200000, and twenty times cheaper. 0 keeps every pixel.
  int max_points = 10000;
  double max_plane_rms_m = 0.015; ///< A top face is planar; more means a bent/merged segment.
  /// A segment failing the plane test is split where neighbouring depths
  /// step by more than this (D415 noise between neighbours at 2 m: ~1 cm).
  double max_depth_step_m = 0.03;
  int min_part_area_px = 400;  ///< Smaller parts of a split (flying-pixel strips) are dropped.
  DimensionTolerance dimensions;  ///< Check of the quad's length/width and the OBB thickness.
  /// Colour-free segments get the type whose length and width are both
  /// within this distance (closest wins); they must be complete faces.
  double classification_tolerance_m = 0.05;
  /// Colour-free segments must also fill their quad this well: pieces of
  /// the ground or of merged faces are not rectangles.
  double min_fill_ratio = 0.85;
  /// Optional "up" direction (unit, camera frame, e.g. from tf). When set
  /// (non-zero), faces whose normal is more than max_tilt_deg from it are not
  /// top faces and are dropped.
  Eigen::Vector3d up_direction = Eigen::Vector3d::Zero();
  /// Truncated-edge test: pixels this far outside a quad edge that are
  /// closer than the face's plane by occluder_margin_m are an occluder.
  double edge_probe_offset_px = 5.0;
  double occluder_margin_m = 0.03;
  double max_tilt_deg = 30.0;
  PlaneFitParams plane;
  QuadFitParams quad;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// Centre of a face from its four corners on its plane: halfway between the
/// midpoints of its two end edges (the corners' mean). The diagonals'
/// intersection is the same point for an exact quad, but on a long face it
/// turns an error of one corner across the face into a shift along it,
/// amplified by the aspect ratio (0.8x for a 0.6 x 0.2 m plate, 2.3x for a
/// 1.8 m one); the mean moves by a quarter of the corner's error, in its
/// direction.
Eigen::Vector3d faceCentre(const std::array<Eigen::Vector3d, 4>& corners_m);

/// Either a candidate or the reason the segment was dropped.
using RoiResult = std::variant<BrickCandidate, std::string>;

/// Everything one segment turned into (several candidates when it was split).
struct RoiOutcome
{
  std::vector<BrickCandidate> candidates;
  std::vector<std::string> rejections;
};

class RoiFilter
{
public:
  /// Throws ConfigError for a bad parameter.
  RoiFilter(const BrickCatalogue& catalogue, const RoiFilterParams& params, const CloudProcessorParams& cloud_params);

  /// Filters one segment. HSV segments are checked against their type;
  /// colour-free ones are classified by their dimensions.
  /// `cloud_timings` (optional) accumulates the cloud-processing time.
  RoiResult filter(const RgbdFrame& frame, const Segment& segment, CloudProcessingTimings* cloud_timings = nullptr) const;

  /// Like filter(), but a segment that measures as n >= 2 plates of its type
  /// lying side by side (rows of an organised pile, whose gaps perspective
  /// hides) is cut into n parts, each filtered on its own (see
  /// splitSideBySide()); one that is not planar is split where its depth
  /// steps (see splitAtDepthSteps()).
  RoiOutcome filterSplitting(const RgbdFrame& frame, const Segment& segment,
                             CloudProcessingTimings* cloud_timings = nullptr) const;

private:
  /// Points, plane, OBB and outline geometry; the reason when it fails.
  std::optional<std::string> measure(const RgbdFrame& frame, const Segment& segment,
                                     CloudProcessingTimings* cloud_timings, BrickCandidate& candidate) const;
  /// Quad, corners, T1/T2, centre and dimensions from the mask and the plane.
  std::optional<std::string> fitOutline(const RgbdFrame& frame, const Segment& segment, BrickCandidate& candidate) const;
  std::optional<std::string> assignType(const Segment& segment, BrickCandidate& candidate) const;

  BrickCatalogue catalogue_;
  RoiFilterParams params_;
  CloudProcessor cloud_processor_;
};
}  // namespace brick_pose
