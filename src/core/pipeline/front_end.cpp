#include "brick_pose/pipeline/front_end.h"

#include <algorithm>
#include <chrono>
#include <iterator>
#include <optional>
#include <sstream>

#include "brick_pose/common/elapsed.h"
#include "brick_pose/common/enum_names.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/frame/organized_cloud.h"
#include "brick_pose/pipeline/face_pieces.h"
#include "brick_pose/common/parallel_for.h"

namespace brick_pose
{
namespace
{

/// Pieces of an occluded plate may each be shorter than the visible
/// fraction the front end accepts, and only their union long enough: the ROI
/// filter lets small pieces through, and the front end applies the real
/// minimum after joining them.
constexpr double kMinPieceFraction = 0.15;

RoiFilterParams pieceFilterParams(const FrontEndParams& params)
{
  params.roi.validate();  // as configured, before the piece threshold replaces one value
  RoiFilterParams roi = params.roi;
  roi.worker_threads = std::max(1, params.worker_threads);  // the bricks of a merged face on the front end's threads
  roi.tiling.worker_threads = roi.worker_threads;            // and its seam evidence
  if (params.merge_face_pieces)
    roi.dimensions.min_visible_fraction = std::min(roi.dimensions.min_visible_fraction, kMinPieceFraction);
  return roi;
}

/// The colour search runs on the front end's threads.
HsvSegmenterParams segmenterParams(const FrontEndParams& params)
{
  HsvSegmenterParams hsv = params.hsv;
  hsv.worker_threads = std::max(1, params.worker_threads);
  return hsv;
}

const BrickCatalogue& nonEmpty(const BrickCatalogue& catalogue)
{
  if (catalogue.empty()) throw ConfigError("front end: the brick catalogue is empty");
  return catalogue;
}

/// The types of `catalogue` with no plate colour (plain boxes): in mode hsv
/// they are found by colour-free segmentation instead.
std::optional<BrickCatalogue> uncolouredTypes(const BrickCatalogue& catalogue)
{
  std::vector<BrickType> types;
  for (const BrickType& type : catalogue.types())
    if (!type.hasPlateColour()) types.push_back(type);
  if (types.empty()) return std::nullopt;
  return BrickCatalogue(std::move(types));
}

/// Pixels the HSV segments took, for the colour-free pass to leave alone.
cv::Mat coveredPixels(const RgbdFrame& frame, const std::vector<Segment>& segments)
{
  cv::Mat covered = cv::Mat::zeros(frame.height_px(), frame.width_px(), CV_8UC1);
  for (const Segment& segment : segments) covered(segment.bounding_box_px).setTo(255, segment.mask);
  return covered;
}
}  // namespace

std::string rejectionCategory(const std::string& reason)
{
  // Most specific phrases first: a split part's reason embeds another one.
  static const std::vector<std::pair<const char*, const char*>> kPhrases = {
      {"cut by an occluder or the image border", "cut by an occluder or the border"},
      {"minimum visible fraction", "too small a part"},
      {"segment fills", "not a rectangle"},
      {"not a flat face", "not flat"},
      {"plane rms", "not flat"},
      {"face tilt", "too tilted"},
      {"matches no catalogue type", "wrong size"},
      {"length", "wrong size"},
      {"width", "wrong size"},
      {"thickness", "wrong size"},
      {"depth pixels, need", "too few points"},
      {"no points left", "too few points"},
      {"collinear", "no outline"},
      {"quadrilateral", "no outline"},
      {"ray misses", "no outline"},
      {"unknown brick type", "unknown type"},
  };
  for (const auto& [phrase, category] : kPhrases)
    if (reason.find(phrase) != std::string::npos) return category;
  return "other";
}

constexpr EnumName<SegmentationMode> kSegmentationModeNames[] = {
    {SegmentationMode::kHsv, "hsv"}, {SegmentationMode::kRegionGrowing, "region_growing"}, {SegmentationMode::kColourFree, "colour_free"}};

SegmentationMode parseSegmentationMode(const std::string& name)
{
  return parseEnumName("parameter 'mode' (segmentation)", name, kSegmentationModeNames);
}

std::string toString(SegmentationMode mode) { return enumName(mode, kSegmentationModeNames); }

CloudProcessorParams FrontEndParams::defaultSegmentCloudParams()
{
  CloudProcessorParams params;
  params.crop_enabled = true;
  params.voxel_enabled = false;
  params.outlier_removal_enabled = false;
  params.mls_enabled = false;
  return params;
}

FrontEnd::FrontEnd(const BrickCatalogue& catalogue, const FrontEndParams& params)
  : catalogue_(nonEmpty(catalogue)),
    params_(params),
    hsv_segmenter_(segmenterParams(params)),
    region_growing_segmenter_(params.region_growing),
    colour_free_segmenter_(params.colour_free),
    roi_filter_(catalogue, pieceFilterParams(params), params.cloud)
{
  params_.up.validate();
  if (params.mode == SegmentationMode::kHsv)
    if (const auto uncoloured = uncolouredTypes(catalogue_))
      uncoloured_roi_filter_.emplace(*uncoloured, pieceFilterParams(params), params.cloud);
}

std::vector<Segment> FrontEnd::segment(const RgbdFrame& frame) const
{
  switch (params_.mode)
  {
    case SegmentationMode::kHsv: return hsvSegments(frame);
    case SegmentationMode::kRegionGrowing: return region_growing_segmenter_.segment(frame);
    case SegmentationMode::kColourFree: return colourFreeSegments(frame);
  }
  return {};
}

std::vector<Segment> FrontEnd::hsvSegments(const RgbdFrame& frame) const
{
  std::vector<Segment> segments = hsv_segmenter_.segment(frame, catalogue_);
  if (!uncoloured_roi_filter_) return segments;
  // Types without a plate colour: colour-free segments (their type_name is
  // empty) of the pixels no plate colour took.
  std::vector<Segment> planar = colourFreeSegments(frame, coveredPixels(frame, segments));
  std::move(planar.begin(), planar.end(), std::back_inserter(segments));
  return segments;
}

std::vector<Segment> FrontEnd::colourFreeSegments(const RgbdFrame& frame, const cv::Mat& excluded) const
{
  const std::optional<Eigen::Vector4d> given = givenSupportPlane(frame);
  return colour_free_segmenter_
      .segmentPlanes(frame, excluded, nullptr, !params_.skip_supporting_plane, given,
                     given ? std::nullopt : dominantPlane(frame))
      .segments;
}

std::optional<Eigen::Vector4d> FrontEnd::dominantPlane(const RgbdFrame& frame) const
{
  // The RANSAC frameContext() runs when no support is given: a quick plane
  // the colour-free clustering may start from (it is not taken for the
  // support there).
  const UpDirection dominant = estimateSupportPlaneUp(frame, params_.up);
  if (!dominant.has_support_plane) return std::nullopt;
  Eigen::Vector4d plane;
  plane << dominant.support_normal, dominant.support_offset_m;
  return plane;
}

std::optional<Eigen::Vector4d> FrontEnd::givenSupportPlane(const RgbdFrame& frame) const
{
  // The same precedence as frameContext(): the frame's own plane first.
  UpDirection given;
  if (frame.support_in_camera) given = givenSupport(*frame.support_in_camera);
  if (!given.support_given) given = givenSupport(params_.roi.support_plane);
  if (!given.support_given) return std::nullopt;
  Eigen::Vector4d plane;
  plane << given.support_normal, given.support_offset_m;
  return plane;
}

void FrontEnd::filterSegments(const RgbdFrame& frame, const std::vector<Segment>& segments,
                              FrontEndResult& result) const
{
  const auto roi_start = SteadyClock::now();
  const double cloud_ms_before = result.timings.cloud.total();
  // Each segment's outcome in its own slot: the merge below keeps the
  // segments' order whatever thread filtered them.
  std::vector<RoiOutcome> outcomes(segments.size());
  std::vector<CloudProcessingTimings> cloud_timings(segments.size());
  std::vector<double> work_ms(segments.size(), 0.0);
  const FrameContext context = frameContext(frame, segments);
  result.up = context.up;
  parallelFor(static_cast<int>(segments.size()), params_.worker_threads, [&](int i) {
    const auto start = SteadyClock::now();
    // In mode hsv a segment without a type is a colour-free one, for the
    // types without a plate colour only.
    const bool uncoloured_only = uncoloured_roi_filter_ && segments[i].type_name.empty();
    const RoiFilter& filter = uncoloured_only ? *uncoloured_roi_filter_ : roi_filter_;
    outcomes[i] = filter.filterSplitting(frame, segments[i], context, &cloud_timings[i]);
    work_ms[i] = millisecondsSince(start);
  });
  CloudProcessingTimings cloud_work;
  double total_work_ms = 0.0;
  // Reserved: a growing vector of candidates would copy them.
  std::size_t candidate_count = result.candidates.size(), rejection_count = result.rejections.size();
  for (const RoiOutcome& outcome : outcomes)
  {
    candidate_count += outcome.candidates.size();
    rejection_count += outcome.rejections.size();
  }
  result.candidates.reserve(candidate_count);
  result.rejections.reserve(rejection_count);
  for (std::size_t i = 0; i < segments.size(); ++i)
  {
    appendOutcome(segments[i], std::move(outcomes[i]), result);
    cloud_work += cloud_timings[i];
    total_work_ms += work_ms[i];
  }
  // Threads overlap: the wall time is split between cloud processing and
  // the rest of the ROI stage in proportion to the work each took.
  const double wall_ms = millisecondsSince(roi_start);
  const double wall_per_work = total_work_ms > 0.0 ? std::min(1.0, wall_ms / total_work_ms) : 1.0;
  result.timings.cloud += cloud_work.scaled(wall_per_work);
  if (params_.merge_face_pieces) mergeFacePieces(frame, context, result);
  dropSmallPieces(result);
  // The ROI stage is its wall time less the cloud processing done inside it
  // (the merge above re-measures joined pieces too).
  result.timings.roi_ms =
      std::max(0.0, millisecondsSince(roi_start) - (result.timings.cloud.total() - cloud_ms_before));
}

void FrontEnd::appendOutcome(const Segment& segment, RoiOutcome outcome, FrontEndResult& result)
{
  std::move(outcome.candidates.begin(), outcome.candidates.end(), std::back_inserter(result.candidates));
  for (RoiRejection& rejection : outcome.rejections)
  {
    // A part's reason is about that part: reported over its own footprint,
    // not over the whole layer it was cut from.
    const bool of_part = !rejection.part_box_px.empty();
    const std::string category = rejectionCategory(rejection.reason);
    result.rejections.push_back({segment.type_name, of_part ? rejection.part_box_px : segment.bounding_box_px,
                                 of_part ? rejection.part_area_px : segment.area_px, std::move(rejection.reason),
                                 category});
  }
}

FrameContext FrontEnd::frameContext(const RgbdFrame& frame, const std::vector<Segment>& segments) const
{
  FrameContext context = roi_filter_.defaultContext();
  // The frame's own up (tf at its stamp) wins over a configured one.
  if (frame.up_in_camera && frame.up_in_camera->allFinite() && frame.up_in_camera->norm() > 1e-9)
  {
    context.up.up = frame.up_in_camera->normalized();
    context.up.source = UpSource::kGiven;
  }
  // The plane the pile stands on, from tf, wins over a configured one.
  if (frame.support_in_camera) context.up = withGivenSupport(context.up, *frame.support_in_camera);
  if (context.up.support_given) return context;
  const UpDirection support = estimateSupportPlaneUp(frame, params_.up);
  if (context.up.known())
  {
    // Up from tf; the dominant plane is the support when it is level.
    constexpr double kLevelCos = 0.966;  // 15 deg
    if (support.known() && support.up.dot(context.up.up) >= kLevelCos)
    {
      context.up.has_support_plane = true;
      context.up.support_normal = support.support_normal;
      context.up.support_offset_m = support.support_offset_m;
      context.up.support_fraction = support.support_fraction;
    }
    return context;
  }
  context.up = support;
  if (context.up.known() || segments.empty()) return context;
  // No plane dominates the view (a close-up of a pile): the tops of a pile
  // face one way, so the faces' area-weighted dominant normal is up.
  constexpr int kPointsPerSegment = 300;
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> weights;
  for (const Segment& segment : segments)
  {
    if (static_cast<int>(segment.pixel_indices.size()) < params_.roi.min_points) continue;
    std::vector<int> sample;
    const std::size_t step = std::max<std::size_t>(1, segment.pixel_indices.size() / kPointsPerSegment);
    for (std::size_t i = 0; i < segment.pixel_indices.size(); i += step) sample.push_back(segment.pixel_indices[i]);
    const PlaneFit plane = fitPlane(*backProjectPixels(frame, sample), params_.roi.plane);
    if (!plane.valid || plane.rms_m > params_.roi.max_plane_rms_m) continue;
    normals.push_back(plane.normal);
    weights.push_back(segment.area_px);
  }
  context.up = dominantFaceNormal(normals, weights, params_.up);
  return context;
}

void FrontEnd::dropSmallPieces(FrontEndResult& result) const
{
  const DimensionTolerance& tolerance = params_.roi.dimensions;
  auto& candidates = result.candidates;
  for (auto it = candidates.begin(); it != candidates.end();)
  {
    // (a box resting on a side: the size of its face up)
    const std::optional<BrickType> type = catalogue_.findResting(it->type_name);
    const double min_length_m = type ? tolerance.min_visible_fraction * type->length_m - tolerance.tolerance_m : 0.0;
    const double min_width_m = type ? tolerance.min_visible_fraction * type->width_m - tolerance.tolerance_m : 0.0;
    // The longer measured side may be the width of a short visible piece.
    const double longer = std::max(it->length_m, it->width_m), shorter = std::min(it->length_m, it->width_m);
    if (longer >= std::max(min_length_m, min_width_m) && shorter >= std::min(min_length_m, min_width_m))
    {
      ++it;
      continue;
    }
    std::ostringstream reason;
    reason.precision(3);
    reason << it->type_name << ": visible part " << it->length_m << " x " << it->width_m
           << " m is below the minimum visible fraction " << tolerance.min_visible_fraction;
    result.rejections.push_back({it->type_name, it->bounding_box_px, it->area_px, reason.str(), "too small a part"});
    it = candidates.erase(it);
  }
}

void FrontEnd::mergeFacePieces(const RgbdFrame& frame, const FrameContext& context, FrontEndResult& result) const
{
  // Cheap test before the full ROI filtration of the joined segment: all
  // eight corners must fit in one plate, measured along and across the
  // first piece's long axis.
  auto fitsOnePlate = [&](const BrickCandidate& a, const BrickCandidate& b) {
    const BrickType* type = catalogue_.find(a.type_name);
    if (!type) return false;
    const Eigen::Vector3d along = (a.corners_m[1] - a.corners_m[0]).normalized();
    const Eigen::Vector3d across = a.normal.cross(along).normalized();
    double along_min = 1e9, along_max = -1e9, across_min = 1e9, across_max = -1e9;
    for (const BrickCandidate* piece : {&a, &b})
      for (const Eigen::Vector3d& corner : piece->corners_m)
      {
        along_min = std::min(along_min, corner.dot(along));
        along_max = std::max(along_max, corner.dot(along));
        across_min = std::min(across_min, corner.dot(across));
        across_max = std::max(across_max, corner.dot(across));
      }
    const double tolerance_m = params_.roi.dimensions.tolerance_m;
    const double extent_a = along_max - along_min, extent_b = across_max - across_min;
    const double longer = std::max(extent_a, extent_b), shorter = std::min(extent_a, extent_b);
    return longer <= type->length_m + tolerance_m && shorter <= type->width_m + tolerance_m;
  };
  std::vector<BrickCandidate>& candidates = result.candidates;
  for (bool merged = true; merged;)
  {
    merged = false;
    for (std::size_t i = 0; i < candidates.size() && !merged; ++i)
      for (std::size_t j = i + 1; j < candidates.size() && !merged; ++j)
      {
        if (!mayBePiecesOfOneFace(candidates[i], candidates[j], params_.merge_max_angle_deg,
                                  params_.merge_max_offset_m) ||
            !fitsOnePlate(candidates[i], candidates[j]))
          continue;
        RoiResult joined =
            roi_filter_.filter(frame, joinSegments(candidates[i], candidates[j]), context, &result.timings.cloud);
        auto* candidate = std::get_if<BrickCandidate>(&joined);
        if (!candidate) continue;
        candidates[i] = std::move(*candidate);
        candidates.erase(candidates.begin() + static_cast<std::ptrdiff_t>(j));
        merged = true;
      }
  }
}

FrontEndResult FrontEnd::process(const RgbdFrame& frame) const
{
  FrontEndResult result;
  const auto frame_start = SteadyClock::now();
  const std::vector<Segment> segments = segment(frame);
  result.timings.segmentation_ms = millisecondsSince(frame_start);
  filterSegments(frame, segments, result);
  result.timings.total_ms = millisecondsSince(frame_start);
  return result;
}
}  // namespace brick_pose
