#pragma once
// The perception front end: segmentation, cloud processing and ROI
// filtration of one RgbdFrame, returning brick candidates, per-stage timings
// and the reasons segments were dropped.

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/cloud/cloud_processor.h"
#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/roi/brick_candidate.h"
#include "brick_pose/roi/roi_filter.h"
#include "brick_pose/roi/up_direction.h"
#include "brick_pose/segmentation/colour_free_segmenter.h"
#include "brick_pose/segmentation/hsv_segmenter.h"
#include "brick_pose/segmentation/region_growing_segmenter.h"

namespace brick_pose
{
enum class SegmentationMode
{
  kHsv,            ///< Plate colour per catalogue type (default, fast); types without one colour-free.
  kRegionGrowing,  ///< Colour-free planar faces classified by size (the paper's PCL region growing; slow).
  kColourFree,     ///< Colour-free planar faces classified by size (cell clustering; real time).
};

/// "hsv", "region_growing" or "colour_free"; throws ConfigError for anything else.
SegmentationMode parseSegmentationMode(const std::string& name);
std::string toString(SegmentationMode mode);

struct FrontEndParams
{
  SegmentationMode mode = SegmentationMode::kHsv;
  HsvSegmenterParams hsv;
  RegionGrowingParams region_growing;
  ColourFreeParams colour_free;
  /// colour_free mode: the supporting plane (ground, table; see
  /// PlanarSegments) is not passed to ROI filtration. It is no brick, and
  /// measuring and splitting a segment of most of the image costs ten times
  /// the rest of the front end.
  bool skip_supporting_plane = true;
  /// Applied to each segment's points, not to the whole frame. Defaults
  /// keep the front end fast: only the depth crop is on. Large segments are
  /// already thinned in the image (RoiFilterParams::max_points), the robust
  /// plane fit drops outliers, and the outline geometry comes from the mask,
  /// so the voxel grid, SOR and MLS are optional extras.
  CloudProcessorParams cloud = defaultSegmentCloudParams();
  RoiFilterParams roi;
  /// How "up" is found in a frame when roi.up_direction (tf) is not set.
  UpDirectionParams up;
  /// An occluder lying across a plate splits it into pieces. Incomplete
  /// candidates of one type on one plane (normals within merge_max_angle_deg,
  /// each centroid within merge_max_offset_m of the other's plane) are
  /// joined when the joined segment still passes ROI filtration (so two
  /// different plates side by side are not). Pieces down to 15% of a plate
  /// take part; the minimum visible fraction applies to the joined result.
  bool merge_face_pieces = true;
  double merge_max_angle_deg = 5.0;
  double merge_max_offset_m = 0.02;
  /// Segments are filtered on this many threads (1: in the caller's thread).
  /// A pile's segments are independent and a long brick's face alone can
  /// take as long as the rest, so two workers on a 2-core machine about
  /// halve the ROI stage. The same threads search the plate colours
  /// (HsvSegmenterParams::worker_threads), read the seam evidence of a
  /// merged face (FaceTilingParams::worker_threads) and measure the bricks
  /// it is cut into (RoiFilterParams::worker_threads).
  int worker_threads = 2;

  static CloudProcessorParams defaultSegmentCloudParams();
};

/// Wall time of each stage of one frame, milliseconds.
struct FrontEndTimings
{
  double segmentation_ms = 0.0;
  CloudProcessingTimings cloud;  ///< Summed over segments.
  double roi_ms = 0.0;           ///< ROI filtration without the cloud processing inside it.
  double total_ms = 0.0;
};

/// A segment that was not a brick, and why.
struct Rejection
{
  std::string type_name;  ///< Empty for colour-free segments.
  cv::Rect bounding_box_px;
  int area_px = 0;
  std::string reason;
  /// A few words that group reasons for counting ("too small", "not flat",
  /// "cut by an occluder or the border"); see rejectionCategory().
  std::string category;
};

/// The category of a rejection reason, for the stages' counts of what they
/// dropped and why: "cut by an occluder or the border", "too small a part",
/// "not a rectangle", "not flat", "too tilted", "wrong size", "too few
/// points", "no outline", "unknown type" or "other".
std::string rejectionCategory(const std::string& reason);

struct FrontEndResult
{
  std::vector<BrickCandidate> candidates;
  std::vector<Rejection> rejections;
  /// Which way was taken as up (and from what) for the top-face check.
  UpDirection up;
  FrontEndTimings timings;
};

class FrontEnd
{
public:
  /// Throws ConfigError for an empty catalogue or a bad parameter.
  FrontEnd(const BrickCatalogue& catalogue, const FrontEndParams& params = FrontEndParams());

  /// Segmentation then ROI filtration of one frame.
  FrontEndResult process(const RgbdFrame& frame) const;

  /// The two halves of process(), for running them in separate nodelets:
  /// stage 2, the segments of the configured mode ...
  std::vector<Segment> segment(const RgbdFrame& frame) const;
  /// ... and stage 3, appending candidates, rejections and the ROI and cloud
  /// timings of `segments` to `result`.
  void filterSegments(const RgbdFrame& frame, const std::vector<Segment>& segments, FrontEndResult& result) const;

  const FrontEndParams& params() const { return params_; }

private:
  /// What the whole frame says before its segments are filtered one by
  /// one: up from tf, else the supporting plane, else the faces' dominant
  /// normal.
  FrameContext frameContext(const RgbdFrame& frame, const std::vector<Segment>& segments) const;
  /// The plate-colour segments, then (when the catalogue has types without a
  /// plate colour) the colour-free segments of the pixels left.
  std::vector<Segment> hsvSegments(const RgbdFrame& frame) const;
  /// The colour-free segments, without the supporting plane when so configured.
  std::vector<Segment> colourFreeSegments(const RgbdFrame& frame, const cv::Mat& excluded = cv::Mat()) const;
  /// The dominant plane of the frame (estimateSupportPlaneUp), if one holds
  /// enough of it: n and d with n . x + d the height above it.
  std::optional<Eigen::Vector4d> dominantPlane(const RgbdFrame& frame) const;
  /// The plane the pile stands on when it is given (the frame's from tf,
  /// else RoiFilterParams::support_plane), as a unit normal and offset.
  std::optional<Eigen::Vector4d> givenSupportPlane(const RgbdFrame& frame) const;
  /// Joins pieces of one face (see FrontEndParams::merge_face_pieces).
  void mergeFacePieces(const RgbdFrame& frame, const FrameContext& context, FrontEndResult& result) const;
  /// Drops (as rejections) candidates below RoiFilterParams' minimum visible
  /// fraction once pieces are joined.
  void dropSmallPieces(FrontEndResult& result) const;
  static void appendOutcome(const Segment& segment, RoiOutcome outcome, FrontEndResult& result);

  BrickCatalogue catalogue_;
  FrontEndParams params_;
  HsvSegmenter hsv_segmenter_;
  RegionGrowingSegmenter region_growing_segmenter_;
  ColourFreeSegmenter colour_free_segmenter_;
  RoiFilter roi_filter_;
  /// Mode hsv with types without a plate colour: ROI filtration of the
  /// colour-free segments against those types only.
  std::optional<RoiFilter> uncoloured_roi_filter_;
};
}  // namespace brick_pose
