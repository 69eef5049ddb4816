// RoiFilter, part 1 of 3: measuring a segment's face (plane, quad, edges)
// and judging it complete. roi_filter_tiling.cpp splits merged faces into
// bricks; roi_filter_typing.cpp tells their types.

#include "brick_pose/roi/roi_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/angles.h"
#include "brick_pose/common/errors.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/frame/organized_cloud.h"
#include "brick_pose/roi/catalogue_size_placement.h"
#include "brick_pose/roi/inset_fill.h"
#include "brick_pose/roi/plate_splitter.h"
#include "brick_pose/roi/size_placed_edge.h"
#include "brick_pose/roi/type_evidence.h"

#include "roi_filter_internal.h"

namespace brick_pose
{
using roi_internal::addTypeDoubt;
using roi_internal::anyTruncated;
using roi_internal::describe;
using roi_internal::partRejection;
using roi_internal::sideAxis;
using roi_internal::kMaxUntiledForAlternative;
using roi_internal::kMaxUntiledWithSeenSeams;
using roi_internal::kMinSeenCutShare;
using roi_internal::kFaintSeamStrength;
using roi_internal::kPairedSeamStrength;

namespace
{
template <typename T>
std::array<T, 4> rotated(const std::array<T, 4>& values, int start)
{
  std::array<T, 4> out;
  for (int k = 0; k < 4; ++k) out[k] = values[(start + k) % 4];
  return out;
}

pcl::PointCloud<pcl::PointXYZ>::Ptr planeInliers(const pcl::PointCloud<pcl::PointXYZ>& cloud, const PlaneFit& plane,
                                                 const PlaneFitParams& params)
{
  const double max_distance_m = std::max(params.min_inlier_distance_m, params.mad_factor * plane.rms_m);
  pcl::PointCloud<pcl::PointXYZ>::Ptr inliers(new pcl::PointCloud<pcl::PointXYZ>);
  inliers->reserve(cloud.size());
  for (const auto& point : cloud)
    if (std::abs(plane.signedDistance(Eigen::Vector3d(point.x, point.y, point.z))) <= max_distance_m)
      inliers->push_back(point);
  inliers->header = cloud.header;
  return inliers;
}

/// Mean distance between the long edges 0->1 and 3->2 (from the middle of
/// each to the line of the other). Equal to the short edges of a rectangle,
/// and still the plate's width when an occluder or the image border cuts the
/// face slantwise and the quad's short sides follow that cut.
double longEdgeSeparation(const std::array<Eigen::Vector3d, 4>& c)
{
  auto distanceToLine = [](const Eigen::Vector3d& point, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return (point - a).cross((b - a).normalized()).norm();
  };
  return 0.5 * (distanceToLine(0.5 * (c[0] + c[1]), c[3], c[2]) + distanceToLine(0.5 * (c[3] + c[2]), c[0], c[1]));
}

/// A quad corner nearer the image's outer edge than this (px; 2 px from the
/// centre of the outermost pixels) may be the border's cut rather than the
/// face's corner: measured corners are within 1.1 px of the truth at p90 on
/// the rig.
constexpr double kCornerBorderMarginPx = 2.5;

/// Whether the cuts of `tiling` show a trace of a seam (see kFaintSeamStrength).
bool cutsShowSeamTraces(const RgbdFrame& frame, const PlaneFit& plane, const FaceTiling& tiling,
                        const EdgeEvidenceParams& params)
{
  int paired = 0;
  for (const FaceTile& tile : tiling.tiles)
    for (int k = 0; k < 4; ++k)
    {
      if (!tile.cut[k]) continue;
      const double strength = scoreSeam(frame, plane, frame.camera.project(tile.corners_m[k]),
                                        frame.camera.project(tile.corners_m[(k + 1) % 4]), params)
                                  .strength;
      if (strength >= kFaintSeamStrength || (strength >= kPairedSeamStrength && ++paired >= 2)) return true;
    }
  return false;
}

/// Whether the smaller tops of `alternative` explain a face judged complete
/// well enough, with a seam or its trace where they meet, to doubt it.
bool smallerTopsExplain(const RgbdFrame& frame, const PlaneFit& plane, const FaceTiling& alternative,
                        const EdgeEvidenceParams& params)
{
  if (alternative.tiles.size() < 2) return false;
  const bool seams_along_the_cuts =
      alternative.cuts > 0 && alternative.seen_cuts >= kMinSeenCutShare * alternative.cuts;
  if (seams_along_the_cuts && alternative.untiled_fraction <= kMaxUntiledWithSeenSeams) return true;
  return alternative.untiled_fraction <= kMaxUntiledForAlternative &&
         (alternative.seen_cuts > 0 || cutsShowSeamTraces(frame, plane, alternative, params));
}

/// Share of the quad's pixels outside the segment whose depth lies on the
/// face's plane (within step_m): the face seen going on where the segment
/// stops. Pixels covered by something nearer, or without depth, do not count.
double unsegmentedCoplanarFraction(const RgbdFrame& frame, const BrickCandidate& candidate, double step_m)
{
  std::vector<cv::Point> polygon;
  for (const Eigen::Vector2d& corner : candidate.corners_px)
    polygon.emplace_back(roundToInt(corner.x()), roundToInt(corner.y()));
  const cv::Rect image(0, 0, frame.width_px(), frame.height_px());
  const cv::Rect box = cv::boundingRect(polygon) & image;
  if (box.area() == 0 || !candidate.plane.valid) return 0.0;
  cv::Mat quad = cv::Mat::zeros(box.size(), CV_8UC1);
  for (cv::Point& point : polygon) point -= box.tl();
  cv::fillConvexPoly(quad, polygon, cv::Scalar(255));
  const cv::Rect& segment_box = candidate.bounding_box_px;
  const bool has_mask = !candidate.mask.empty();
  int quad_px = 0, coplanar_px = 0;
  for (int v = box.y; v < box.br().y; ++v)
  {
    const unsigned char* quad_row = quad.ptr<unsigned char>(v - box.y);
    const bool row_in_segment = has_mask && v >= segment_box.y && v < segment_box.br().y;
    const unsigned char* mask_row = row_in_segment ? candidate.mask.ptr<unsigned char>(v - segment_box.y) : nullptr;
    for (int u = box.x; u < box.br().x; ++u)
    {
      if (!quad_row[u - box.x]) continue;
      ++quad_px;
      if (mask_row && u >= segment_box.x && u < segment_box.br().x && mask_row[u - segment_box.x]) continue;
      const float z = frame.depthAt(u, v);
      if (!std::isnan(z) && std::abs(candidate.plane.signedDistance(frame.camera.backProject(u, v, z))) < step_m)
        ++coplanar_px;
    }
  }
  return quad_px > 0 ? static_cast<double>(coplanar_px) / quad_px : 0.0;
}

/// The image direction away from `inside_px` across quad edge k (corner k
/// to k + 1), not unit.
Eigen::Vector2d outwardOf(const QuadCorners& corners_px, int k, const Eigen::Vector2d& inside_px)
{
  const Eigen::Vector2d& a = corners_px[k];
  const Eigen::Vector2d& b = corners_px[(k + 1) % 4];
  const Eigen::Vector2d outward(b.y() - a.y(), a.x() - b.x());
  return outward.dot(0.5 * (a + b) - inside_px) < 0.0 ? Eigen::Vector2d(-outward) : outward;
}

/// What lies beyond each quad edge (see edge_evidence.h). A step up to a
/// wall as high as something resting on the face could be, or to walls of
/// several heights, is an occlusion (not a drop beside walls: the face ends
/// there); its height goes to `resting_wall_m` when the edge's ends are
/// clear. `beside_wall` marks the edges with walls the camera sees.
EdgeKinds classifyEdges(const RgbdFrame& frame, const BrickCandidate& candidate, const EdgeEvidenceParams& params,
                        const BrickCatalogue& catalogue, double resting_height_margin_m,
                        std::array<double, 4>& resting_wall_m, std::array<bool, 4>& beside_wall)
{
  EdgeKinds kinds;
  resting_wall_m.fill(std::numeric_limits<double>::quiet_NaN());
  beside_wall.fill(false);
  for (int k = 0; k < 4; ++k)
  {
    const Eigen::Vector2d& a = candidate.corners_px[k];
    const Eigen::Vector2d& b = candidate.corners_px[(k + 1) % 4];
    const Eigen::Vector2d outward = outwardOf(candidate.corners_px, k, candidate.centroid_px);
    const EdgeEvidence evidence = classifyEdge(frame, candidate.plane, a, b, outward, params);
    kinds[k] = evidence.kind;
    beside_wall[k] = !std::isnan(evidence.lowest_wall_m);
    const bool several_walls = kinds[k] == EdgeKind::kOcclusion && !std::isnan(evidence.lowest_wall_m);
    if (several_walls ||
        (kinds[k] == EdgeKind::kStepUp && catalogue.couldRiseTo(evidence.outside_offset_m, resting_height_margin_m)))
    {
      kinds[k] = EdgeKind::kOcclusion;
      if (occlusionAtEdgeEnds(frame, candidate.plane, a, b, outward, params, evidence.lowest_wall_m,
                              evidence.highest_wall_m) != EdgeKind::kOcclusion)
        resting_wall_m[k] = evidence.highest_wall_m;
    }
    // (A drop beside walls ends the face whatever their height. Real
    // kinds other than walls carry no wall heights: NaN.)
    if (isRealEdge(kinds[k], true) &&
        occlusionAtEdgeEnds(frame, candidate.plane, a, b, outward, params, evidence.lowest_wall_m,
                            evidence.highest_wall_m) == EdgeKind::kOcclusion)
      kinds[k] = EdgeKind::kOcclusion;
  }
  // The profiles stay clear of the corners, so a corner just past the border
  // (a face a few pixels too long for the image) is only seen here.
  // (Where an edge at that corner already runs along the border, the face
  // is cut there and the other edge keeps its own evidence.)
  for (int k = 0; k < 4; ++k)
    if (!frame.camera.contains(candidate.corners_px[k].x(), candidate.corners_px[k].y(), kCornerBorderMarginPx) &&
        kinds[k] != EdgeKind::kImageBorder && kinds[(k + 3) % 4] != EdgeKind::kImageBorder)
      kinds[k] = kinds[(k + 3) % 4] = EdgeKind::kImageBorder;
  return kinds;
}

double tiltDegrees(const Eigen::Vector3d& normal, const Eigen::Vector3d& up)
{
  const double cos_tilt = normal.dot(up.normalized());
  return std::acos(std::max(-1.0, std::min(1.0, cos_tilt))) * kRadToDeg;
}

/// The reason an edge keeps a face from being complete.
std::string edgeReason(int edge, EdgeKind kind)
{
  const std::string name = "edge " + std::to_string(edge);
  switch (kind)
  {
    case EdgeKind::kImageBorder: return "cut by the image border (" + name + ")";
    case EdgeKind::kOcclusion: return name + " is an occlusion boundary";
    case EdgeKind::kMaskEdge: return name + " continues on the same plane: no step, crease or seam seen";
    case EdgeKind::kNoDepth: return name + " has no depth beyond it";
    case EdgeKind::kOverrun: return name + " is not the face's: the segment runs over it onto another surface";
    case EdgeKind::kColourLine:
      return name + " is only a line in the colour image (print on a box?): no step, crease or groove seen";
    default: return name + " was not examined";
  }
}

/// Every k-th index so that about `max_count` remain (all when max_count is 0).
std::vector<int> thinned(const std::vector<int>& indices, int max_count)
{
  if (max_count <= 0 || static_cast<int>(indices.size()) <= max_count) return indices;
  const std::size_t step = (indices.size() + max_count - 1) / static_cast<std::size_t>(max_count);
  std::vector<int> kept;
  kept.reserve(indices.size() / step + 1);
  for (std::size_t i = 0; i < indices.size(); i += step) kept.push_back(indices[i]);
  return kept;
}

/// Index (0 or 1) of the corner starting the first long edge of a
/// clockwise quad, then moved to the upper of the two long edges.
int longEdgeStart(const QuadCorners& corners_px, const std::array<Eigen::Vector3d, 4>& corners_m)
{
  auto edge = [&](int k) { return (corners_m[(k + 1) % 4] - corners_m[k]).norm(); };
  const int start = edge(0) + edge(2) >= edge(1) + edge(3) ? 0 : 1;
  const Eigen::Vector2d& a = corners_px[start];
  const Eigen::Vector2d& b = corners_px[start + 2];
  const bool a_first = a.y() < b.y() - 1e-9 || (std::abs(a.y() - b.y()) <= 1e-9 && a.x() <= b.x());
  return a_first ? start : start + 2;
}

/// Where the image line through `p` along `along` meets the one through
/// `q` along `other`; `p` itself when they are (nearly) parallel.
Eigen::Vector2d meet(const Eigen::Vector2d& p, const Eigen::Vector2d& along, const Eigen::Vector2d& q,
                     const Eigen::Vector2d& other)
{
  const double cross = along.x() * other.y() - along.y() * other.x();
  if (std::abs(cross) < 1e-9 * along.norm() * other.norm()) return p;
  const Eigen::Vector2d to_q = q - p;
  return p + ((to_q.x() * other.y() - to_q.y() * other.x()) / cross) * along;
}

/// The quad with edge k (corner k to k + 1) moved `shift_px` away from
/// `inside_px`, its corners sliding along the neighbouring edges.
std::array<Eigen::Vector2d, 4> withEdgeMovedOut(std::array<Eigen::Vector2d, 4> corners, int k, double shift_px,
                                                const Eigen::Vector2d& inside_px)
{
  const Eigen::Vector2d& a = corners[k];
  const Eigen::Vector2d& b = corners[(k + 1) % 4];
  const Eigen::Vector2d along = b - a;
  const Eigen::Vector2d on_line = a + shift_px * outwardOf(corners, k, inside_px).normalized();
  const Eigen::Vector2d& before = corners[(k + 3) % 4];
  const Eigen::Vector2d& after = corners[(k + 2) % 4];
  const Eigen::Vector2d new_a = meet(on_line, along, before, a - before);
  const Eigen::Vector2d new_b = meet(on_line, along, after, b - after);
  corners[k] = new_a;
  corners[(k + 1) % 4] = new_b;
  return corners;
}
}  // namespace

Eigen::Vector3d faceCentre(const std::array<Eigen::Vector3d, 4>& corners_m)
{
  return 0.25 * (corners_m[0] + corners_m[1] + corners_m[2] + corners_m[3]);
}

void RoiFilterParams::validate() const
{
  const ParamCheck check("roi filter");
  check.require(min_points >= 3, "min_points", "must be >= 3");
  check.require(max_points >= 0, "max_points", "must be >= 0 (0 keeps every pixel)");
  check.require(max_plane_rms_m > 0.0, "max_plane_rms_m", "must be > 0");
  check.require(max_depth_step_m > 0.0, "max_depth_step_m", "must be > 0");
  check.require(min_part_area_px >= 1, "min_part_area_px", "must be >= 1");
  check.require(dimensions.tolerance_m >= 0.0, "dimensions.tolerance_m", "must be >= 0");
  check.require(dimensions.max_thickness_m >= 0.0, "dimensions.max_thickness_m", "must be >= 0");
  check.require(dimensions.min_visible_fraction > 0.0 && dimensions.min_visible_fraction <= 1.0,
          "dimensions.min_visible_fraction", "must be in (0, 1]");
  check.require(classification_tolerance_m >= 0.0, "classification_tolerance_m", "must be >= 0");
  check.require(min_fill_ratio >= 0.0 && min_fill_ratio <= 1.0, "min_fill_ratio", "must be in [0, 1]");
  check.require(resting_height_margin_m >= 0.0, "resting_height_margin_m", "must be >= 0");
  check.require(size_placed_line_tolerance_m >= 0.0, "size_placed_line_tolerance_m", "must be >= 0");
  check.require(plain_seam_line_share >= 0.0 && plain_seam_line_share < 1.0, "plain_seam_line_share",
                "must be in [0, 1)");
  check.require(height_above_support_tolerance_m >= 0.0 && height_above_support_tolerance_m < 0.1,
                "height_above_support_tolerance_m", "must be in [0, 0.1)");
  check.require(ragged_outline_px >= 0.0, "ragged_outline_px", "must be >= 0");
  check.require(std::isfinite(up_direction.norm()), "up_direction", "must be finite");
  check.require(support_plane.allFinite(), "support_plane", "must be finite");
  check.require(support_plane.isZero() || support_plane.head<3>().norm() > 1e-9, "support_plane",
                "needs a normal (or all zero: not given)");
  check.require(max_tilt_deg > 0.0 && max_tilt_deg <= 90.0, "max_tilt_deg", "must be in (0, 90]");
  check.require(quad.side_band_px > 0.0, "quad.side_band_px", "must be > 0");
  check.require(quad.side_search_px >= 0.0, "quad.side_search_px", "must be >= 0");
  check.require(quad.edge_quantile >= 0.0 && quad.edge_quantile <= 1.0, "quad.edge_quantile", "must be in [0, 1]");
  check.require(quad.min_side_points >= 2, "quad.min_side_points", "must be >= 2");
  check.require(worker_threads >= 1, "worker_threads", "must be >= 1");
  edges.validate();
  tiling.validate();
  sides.validate();
}

RoiFilter::RoiFilter(const BrickCatalogue& catalogue, const RoiFilterParams& params,
                     const CloudProcessorParams& cloud_params)
  : catalogue_(catalogue),
    lying_variants_(lyingVariants(catalogue.types())),
    stack_heights_(StackHeights::of(catalogue.types())),
    catalogue_extents_m_(catalogueExtentsM(catalogue)),
    params_(params),
    cloud_processor_(cloud_params)
{
  params_.validate();
}

FrameContext RoiFilter::defaultContext() const
{
  FrameContext context;
  if (params_.up_direction.norm() > 0.0)
  {
    context.up.up = params_.up_direction.normalized();
    context.up.source = UpSource::kGiven;
  }
  context.up = withGivenSupport(context.up, params_.support_plane);
  return context;
}

RoiResult RoiFilter::filter(const RgbdFrame& frame, const Segment& segment, CloudProcessingTimings* cloud_timings) const
{
  return filter(frame, segment, defaultContext(), cloud_timings);
}

RoiResult RoiFilter::filter(const RgbdFrame& frame, const Segment& segment, const FrameContext& context,
                            CloudProcessingTimings* cloud_timings) const
{
  BrickCandidate candidate;
  if (auto reason = measure(frame, segment, context, cloud_timings, candidate)) return *reason;
  if (auto reason = assignType(frame, context, segment, candidate)) return *reason;
  judgeCompleteness(frame, context, !segment.type_name.empty(), candidate);
  placeOnCatalogueSize(frame, candidate);
  return candidate;
}

RoiOutcome RoiFilter::filterSplitting(const RgbdFrame& frame, const Segment& segment,
                                      CloudProcessingTimings* cloud_timings) const
{
  return filterSplitting(frame, segment, defaultContext(), cloud_timings);
}

RoiOutcome RoiFilter::filterSplitting(const RgbdFrame& frame, const Segment& segment, const FrameContext& context,
                                      CloudProcessingTimings* cloud_timings) const
{
  RoiOutcome outcome = filterSplittingAsMeasured(frame, segment, context, cloud_timings);
  for (BrickCandidate& candidate : outcome.candidates) placeOnCatalogueSize(frame, candidate);
  return outcome;
}

void RoiFilter::placeOnCatalogueSize(const RgbdFrame& frame, BrickCandidate& candidate) const
{
  // Each end's colour edge is read to about a pixel: two ends, two pixels
  // at the face's distance.
  constexpr double kColourAgreementPx = 2.0;
  // A colour segment ends where its colour does, not where depth does.
  if (!params_.place_on_catalogue_size || !candidate.complete || candidate.typed_by_colour) return;
  const std::optional<BrickType> type = catalogue_.findResting(candidate.type_name);
  if (!type) return;
  const std::array<Eigen::Vector3d, 4> corners_m =
      cornersTrimmedToSize(candidate.corners_m, candidate.edge_kinds, type->length_m, type->width_m,
                           params_.dimensions.tolerance_m, colourInsetsM(frame, candidate),
                           kColourAgreementPx * candidate.centroid_m.z() / frame.camera.fx_px);
  QuadCorners corners_px;
  for (int k = 0; k < 4; ++k) corners_px[k] = frame.camera.project(corners_m[k]);
  const double measured_length_m = candidate.length_m, measured_width_m = candidate.width_m;
  placeCorners(frame.camera, corners_px, corners_m, candidate);
  candidate.length_m = measured_length_m;
  candidate.width_m = measured_width_m;
}

std::array<double, 4> RoiFilter::colourInsetsM(const RgbdFrame& frame, const BrickCandidate& candidate) const
{
  std::array<double, 4> insets_m;
  insets_m.fill(std::numeric_limits<double>::quiet_NaN());
  for (int k = 0; k < 4; ++k)
  {
    if (!depthBoundsEdge(candidate.edge_kinds[k]) || !depthBoundsEdge(candidate.edge_kinds[(k + 2) % 4])) continue;
    const Eigen::Vector2d& a = candidate.corners_px[k];
    const Eigen::Vector2d& b = candidate.corners_px[(k + 1) % 4];
    const Eigen::Vector2d outward = outwardOf(candidate.corners_px, k, candidate.centroid_px).normalized();
    const double inset_px = stepEdgeInsetPx(frame, candidate.plane, a, b, outward, params_.edges);
    if (!std::isfinite(inset_px)) continue;
    // The same distance on the face's plane, at the edge's middle.
    const Eigen::Vector2d middle = 0.5 * (a + b);
    Eigen::Vector3d on_edge, inside;
    const Eigen::Vector2d moved = middle - inset_px * outward;
    if (candidate.plane.intersectRay(frame.camera.ray(middle.x(), middle.y()), on_edge) &&
        candidate.plane.intersectRay(frame.camera.ray(moved.x(), moved.y()), inside))
      insets_m[k] = (inside - on_edge).norm();
  }
  return insets_m;
}

RoiOutcome RoiFilter::filterSplittingAsMeasured(const RgbdFrame& frame, const Segment& segment,
                                                const FrameContext& context,
                                                CloudProcessingTimings* cloud_timings) const
{
  RoiOutcome outcome;
  BrickCandidate candidate;
  std::optional<std::string> reason = measure(frame, segment, context, cloud_timings, candidate);
  const bool measured = !reason;
  if (!reason) reason = assignType(frame, context, segment, candidate);
  if (!reason && segment.type_name.empty())
    if (const std::optional<std::string> ruled_out = heightRulesOutType(frame, context, candidate))
    {
      // Its size is one type's top, its height another's: the types
      // standing there tile it (tile() keeps only those), or it stays in
      // doubt, never complete.
      if (std::optional<RoiOutcome> tiled = tile(frame, segment, candidate, context, false, cloud_timings))
        return std::move(*tiled);
      addTypeDoubt(candidate, *ruled_out);
    }
  if (!reason)
  {
    // Colour-free: a face of one brick's size may be smaller bricks end to
    // end. Grooves along every cut say it is. A line (or a groove too faint
    // to cut on) where they would meet leaves it unsure: partial. With
    // nothing at all seen there it is taken as one brick.
    FaceTiling alternative;
    if (segment.type_name.empty() && mayHoldTwoBricks(candidate) && mayShowASeamAcross(frame, segment, candidate))
    {
      // The smaller types only: the face's own type would tile it whole.
      const std::optional<BrickType> own = catalogue_.findResting(candidate.type_name);
      std::vector<const BrickType*> smaller;
      for (const BrickType& type : catalogue_.types())
        if (own && type.length_m * type.width_m < 0.7 * own->length_m * own->width_m) smaller.push_back(&type);
      if (!smaller.empty())
        if (std::optional<RoiOutcome> tiled =
                tile(frame, segment, candidate, context, true, cloud_timings, &alternative, &smaller))
          return std::move(*tiled);
    }
    judgeCompleteness(frame, context, !segment.type_name.empty(), candidate);
    if (candidate.complete && smallerTopsExplain(frame, candidate.plane, alternative, params_.edges))
    {
      candidate.complete = false;
      candidate.partial_reason = "its size is also " + std::to_string(alternative.tiles.size()) + " smaller " +
                                 "catalogue tops touching (" + alternative.tiles.front().type_name + ", ...)" +
                                 ", and a line (or a trace of one) crosses it where they would meet";
      candidate.type_doubt = candidate.partial_reason;  // one brick, or the smaller ones
    }
    // A face that touches a neighbour on its own plane (a seam) lies in a
    // layer of boxes, where smaller ones may lie side by side in its place;
    // a box standing alone ends at steps and creases, and is doubted only
    // where the seam of smaller ones shows (two of them on a stack end at
    // steps too).
    const bool touches_a_neighbour =
        std::any_of(candidate.edge_kinds.begin(), candidate.edge_kinds.end(),
                    [](EdgeKind kind) {
                      return kind == EdgeKind::kSeam || kind == EdgeKind::kColourLine ||
                             kind == EdgeKind::kSizePlacedLine;
                    });
    if (segment.type_name.empty()) doubtComposedTop(frame, context, std::nullopt, touches_a_neighbour, candidate);
    outcome.candidates.push_back(std::move(candidate));
    return outcome;
  }
  // Planar and facing up but no single brick: touching bricks merged.
  if (measured)
    if (std::optional<RoiOutcome> split = splitMerged(frame, segment, candidate, context, cloud_timings))
      return std::move(*split);
  if (measured && publishCutOff(frame, context, segment, candidate, outcome, *reason)) return outcome;
  // Plates at two heights joined through an edge without a clean depth jump
  // give one bent "plane": split where the depth steps, then filter (and
  // tile) each part.
  std::vector<Segment> parts;
  if (!measured && candidate.plane.valid && candidate.plane.rms_m > params_.max_plane_rms_m)
    parts = splitAtDepthSteps(frame, segment, params_.max_depth_step_m, params_.min_part_area_px);
  if (parts.empty())
  {
    outcome.rejections.push_back({*reason, {}, 0});
    return outcome;
  }
  for (const Segment& part : parts)
  {
    BrickCandidate part_candidate;
    std::optional<std::string> part_reason = measure(frame, part, context, cloud_timings, part_candidate);
    const bool part_measured = !part_reason;
    if (!part_reason) part_reason = assignType(frame, context, part, part_candidate);
    if (!part_reason)
    {
      judgeCompleteness(frame, context, !part.type_name.empty(), part_candidate);
      outcome.candidates.push_back(std::move(part_candidate));
      continue;
    }
    if (part_measured)
      if (std::optional<RoiOutcome> split = splitMerged(frame, part, part_candidate, context, cloud_timings))
      {
        std::move(split->candidates.begin(), split->candidates.end(), std::back_inserter(outcome.candidates));
        std::move(split->rejections.begin(), split->rejections.end(), std::back_inserter(outcome.rejections));
        continue;
      }
    if (part_measured && publishCutOff(frame, context, part, part_candidate, outcome, *part_reason)) continue;
    outcome.rejections.push_back(partRejection(part, *part_reason));
  }
  return outcome;
}

bool RoiFilter::publishCutOff(const RgbdFrame& frame, const FrameContext& context, const Segment& segment,
                              BrickCandidate& candidate, RoiOutcome& outcome, std::string& reason) const
{
  // Colour-free only: a colour segment's type is its colour's, cut off or not.
  if (!segment.type_name.empty() || !anyTruncated(candidate)) return false;
  if (std::optional<std::string> no_type = typeCutOffFace(frame, context, candidate))
  {
    reason = *no_type;
    return false;
  }
  judgeCompleteness(frame, context, false, candidate);
  outcome.candidates.push_back(std::move(candidate));
  return true;
}

std::optional<RoiOutcome> RoiFilter::splitMerged(const RgbdFrame& frame, const Segment& segment,
                                                 const BrickCandidate& measured, const FrameContext& context,
                                                 CloudProcessingTimings* cloud_timings) const
{
  if (std::optional<RoiOutcome> tiled = tile(frame, segment, measured, context, false, cloud_timings)) return tiled;
  // Rows of one colour whose bricks are not quite parallel (a wedge of gap
  // between them) fit no rectangles on the merged quad's axes: cut them
  // along their length, evenly or through the visible end of a gap.
  if (segment.type_name.empty()) return std::nullopt;
  std::vector<Segment> parts;
  if (const BrickType* type = catalogue_.find(segment.type_name))
    parts = splitSideBySide(frame, segment, measured, *type, params_.dimensions.tolerance_m);
  if (parts.empty()) return std::nullopt;
  RoiOutcome outcome;
  for (const Segment& part : parts)
  {
    BrickCandidate candidate;
    std::optional<std::string> reason = measure(frame, part, context, cloud_timings, candidate);
    if (!reason) reason = assignType(frame, context, part, candidate);
    if (reason)
    {
      outcome.rejections.push_back(partRejection(part, *reason));
      continue;
    }
    judgeCompleteness(frame, context, true, candidate);
    outcome.candidates.push_back(std::move(candidate));
  }
  return outcome;
}

std::optional<std::string> RoiFilter::measure(const RgbdFrame& frame, const Segment& segment,
                                              const FrameContext& context, CloudProcessingTimings* cloud_timings,
                                              BrickCandidate& candidate, const EdgeEvidenceParams* edges) const
{
  if (static_cast<int>(segment.pixel_indices.size()) < params_.min_points)
    return describe("only", static_cast<double>(segment.pixel_indices.size()), "depth pixels, need",
                    params_.min_points);

  candidate.pixel_indices = segment.pixel_indices;
  candidate.mask = segment.mask;
  candidate.bounding_box_px = segment.bounding_box_px;
  candidate.area_px = segment.area_px;
  const pcl::PointCloud<pcl::PointXYZ>::Ptr raw = backProjectPixels(frame, thinned(segment.pixel_indices, params_.max_points));
  ProcessedCloud processed = cloud_processor_.process(raw);
  if (cloud_timings) *cloud_timings += processed.timings;
  candidate.points = processed.points;
  candidate.smoothed_points = processed.with_normals;
  if (static_cast<int>(candidate.points->size()) < 3) return std::string("no points left after cloud processing");

  candidate.plane = fitPlane(*candidate.points, params_.plane);
  if (!candidate.plane.valid) return std::string("points are collinear: no plane");
  if (candidate.plane.rms_m > params_.max_plane_rms_m)
    return describe("plane rms", candidate.plane.rms_m, "m exceeds", params_.max_plane_rms_m);
  candidate.normal = candidate.plane.normal;
  candidate.tilt_from_up_deg = std::numeric_limits<double>::quiet_NaN();
  if (context.up.known())
  {
    candidate.tilt_from_up_deg = tiltDegrees(candidate.normal, context.up.up);
    if (candidate.tilt_from_up_deg > params_.max_tilt_deg)
    {
      std::ostringstream text;
      text.precision(3);
      text << "not a top face: its normal is " << candidate.tilt_from_up_deg << " deg from up (from "
           << toString(context.up.source) << "), more than " << params_.max_tilt_deg << " (a side face)";
      return text.str();
    }
  }

  // The box of min/max extents is only as good as its worst point: measure it
  // on the plane's inliers (stray pixels of the background that happen to lie
  // near the extended plane, or flying pixels, are dropped here).
  candidate.points = planeInliers(*candidate.points, candidate.plane, params_.plane);
  candidate.obb = computeOrientedBoundingBox(*candidate.points);
  return fitOutline(frame, segment, edges ? *edges : params_.edges, candidate);
}

std::optional<std::string> RoiFilter::fitOutline(const RgbdFrame& frame, const Segment& segment,
                                                 const EdgeEvidenceParams& edges, BrickCandidate& candidate) const
{
  // One blob for a segment from a single component; several for the pieces
  // of a face merged across an occluder.
  const std::vector<std::vector<cv::Point>> outlines = allOutlines(segment.mask, segment.bounding_box_px.tl());
  const std::optional<QuadCorners> quad = fitLeastAreaQuad(outlines, params_.quad);
  if (!quad) return std::string("outline has no enclosing quadrilateral");

  const PinholeCamera& camera = frame.camera;
  std::array<Eigen::Vector3d, 4> corners_m;
  for (int k = 0; k < 4; ++k)
    if (!candidate.plane.intersectRay(camera.ray((*quad)[k].x(), (*quad)[k].y()), corners_m[k]))
      return std::string("a quad corner's ray misses the segment plane");

  double outline_area_px = 0.0;
  for (const auto& outline : outlines) outline_area_px += std::abs(cv::contourArea(outline));
  candidate.fill_ratio = outline_area_px / std::max(1e-9, std::abs(signedAreaPx(*quad)));
  const bool rim_may_explain = candidate.fill_ratio < params_.min_fill_ratio &&
                               shortfallFitsARim(outline_area_px, *quad, params_.ragged_outline_px);
  candidate.inset_fill_ratio = rim_may_explain ? insetFillRatio(outlines, *quad, params_.ragged_outline_px)
                                               : std::numeric_limits<double>::quiet_NaN();
  const int start = longEdgeStart(*quad, corners_m);
  placeCorners(camera, rotated(*quad, start), rotated(corners_m, start), candidate);
  std::array<bool, 4> beside_wall{};
  candidate.edge_kinds = classifyEdges(frame, candidate, edges, catalogue_, params_.resting_height_margin_m,
                                       candidate.resting_wall_m, beside_wall);
  moveEdgesToWallFeet(frame, edges, beside_wall, candidate);
  for (int k = 0; k < 4; ++k)
    candidate.edge_truncated[k] =
        candidate.edge_kinds[k] == EdgeKind::kImageBorder || candidate.edge_kinds[k] == EdgeKind::kOcclusion;
  return std::nullopt;
}

void RoiFilter::placeCorners(const PinholeCamera& camera, const QuadCorners& corners_px,
                             const std::array<Eigen::Vector3d, 4>& corners_m, BrickCandidate& candidate)
{
  candidate.corners_px = corners_px;
  candidate.corners_m = corners_m;
  const auto& c = candidate.corners_m;
  candidate.length_m = 0.5 * ((c[1] - c[0]).norm() + (c[2] - c[3]).norm());
  candidate.width_m = longEdgeSeparation(c);

  candidate.centroid_m = faceCentre(c);
  candidate.centroid_px = camera.project(candidate.centroid_m);
  const Eigen::Vector3d long_axis = ((c[1] - c[0]) + (c[2] - c[3])).normalized();
  candidate.t1_m = candidate.centroid_m + 0.25 * candidate.length_m * long_axis;
  candidate.t2_m = candidate.centroid_m - 0.25 * candidate.length_m * long_axis;
  candidate.t1_px = camera.project(candidate.t1_m);
  candidate.t2_px = camera.project(candidate.t2_m);
}

void RoiFilter::moveEdgesToWallFeet(const RgbdFrame& frame, const EdgeEvidenceParams& edges,
                                    const std::array<bool, 4>& beside_wall, BrickCandidate& candidate) const
{
  // A taller neighbour's depth reaches a few pixels over the face beside
  // it, so the segment, and its quad, end short of the face's edge there
  // (by 1-2 cm a side at 2 m in VGA: a face between two walls measured a
  // smaller box). The colour image shows the edge itself.
  std::array<Eigen::Vector2d, 4> corners_px = candidate.corners_px;
  bool moved = false;
  for (int k = 0; k < 4; ++k)
  {
    if (!beside_wall[k]) continue;
    const double shift_px = wallFootShiftPx(frame, candidate.plane, corners_px[k], corners_px[(k + 1) % 4],
                                            outwardOf(corners_px, k, candidate.centroid_px), edges);
    if (!(shift_px > 0.0)) continue;
    corners_px = withEdgeMovedOut(corners_px, k, shift_px, candidate.centroid_px);
    moved = true;
  }
  if (!moved) return;
  std::array<Eigen::Vector3d, 4> corners_m;
  for (int k = 0; k < 4; ++k)
    if (!candidate.plane.intersectRay(frame.camera.ray(corners_px[k].x(), corners_px[k].y()), corners_m[k])) return;
  placeCorners(frame.camera, corners_px, corners_m, candidate);
}

std::optional<std::string> RoiFilter::shapeDoubt(const RgbdFrame& frame, const FrameContext& context,
                                                 const BrickType& type, const BrickCandidate& candidate) const
{
  // The face goes on, on its own plane, where the segment does not: a mask
  // over part of a printed top, whose quad may still have the catalogue's
  // size. (Where something nearer covers the quad, the brick's extent is
  // still known from its ends: covered, not partial.)
  const double uncovered = unsegmentedCoplanarFraction(frame, candidate, params_.edges.min_step_m);
  if (uncovered > 1.0 - params_.min_fill_ratio)
    return describe("the face continues on its plane outside the segment over", uncovered, "of its quad; limit",
                    1.0 - params_.min_fill_ratio);
  const double tolerance_m = params_.dimensions.tolerance_m;
  if (std::abs(candidate.length_m - type.length_m) > tolerance_m ||
      std::abs(candidate.width_m - type.width_m) > tolerance_m)
  {
    std::ostringstream text;
    text.precision(3);
    text << "visible size " << candidate.length_m << " x " << candidate.width_m << " m is not the catalogue's "
         << type.length_m << " x " << type.width_m << " m";
    // A box lying on a side shows such a face up: the doubt names it.
    if (!candidate.type_doubt.empty()) text << "; " << candidate.type_doubt;
    return text.str();
  }
  if (!context.up.known()) return std::string("up direction unknown: a top face cannot be told from a side face");
  if (!candidate.type_doubt.empty()) return candidate.type_doubt;
  return std::nullopt;
}

std::optional<std::pair<int, std::string>> RoiFilter::placeLinesBySize(const RgbdFrame& frame,
                                                                       const FrameContext& context,
                                                                       const BrickType& type,
                                                                       const std::vector<int>& lines,
                                                                       BrickCandidate& candidate) const
{
  if (lines.empty()) return std::nullopt;
  const double size_off_m =
      std::max(std::abs(candidate.length_m - type.length_m), std::abs(candidate.width_m - type.width_m));
  if (!(params_.size_placed_line_tolerance_m > 0.0 && size_off_m <= params_.size_placed_line_tolerance_m))
    return std::make_pair(lines.front(), describe("and the face's size is", size_off_m, "m off its type's: more than",
                                                  params_.size_placed_line_tolerance_m) +
                                             " for sizes to place it");
  const std::vector<double> extents_m = extentsStandingThere(frame, context, candidate);
  for (const int k : lines)
  {
    const SizePlacedEdge placed =
        judgeSizePlacedEdge(frame, candidate, k, extents_m, params_.dimensions.tolerance_m, params_.edges);
    if (!placed.confirmed) return std::make_pair(k, placed.doubt);
    candidate.edge_kinds[k] = EdgeKind::kSizePlacedLine;
  }
  return std::nullopt;
}

void RoiFilter::judgeCompleteness(const RgbdFrame& frame, const FrameContext& context, bool uniform_colour,
                                  BrickCandidate& candidate) const
{
  candidate.complete = false;
  candidate.partial_reason.clear();
  const std::optional<BrickType> type = catalogue_.findResting(candidate.type_name);
  if (!type)
  {
    candidate.partial_reason = "unknown brick type '" + candidate.type_name + "'";
    return;
  }
  // A type in doubt is said beside an edge's reason too: the reason is all a reader sees.
  const auto partialAtEdge = [&](int k, EdgeKind kind, const std::string& placed_doubt) {
    candidate.partial_reason = edgeReason(k, kind);
    if (!placed_doubt.empty()) candidate.partial_reason += ", " + placed_doubt;
    if (!candidate.type_doubt.empty()) candidate.partial_reason += "; type in doubt: " + candidate.type_doubt;
  };
  // Edges that hide where the brick ends say the most: the border and
  // occluders first, then planes that continue, then missing depth. Lines
  // on a printed face wait: the catalogue may place them (below).
  std::vector<int> lines;
  for (const EdgeKind kind : {EdgeKind::kImageBorder, EdgeKind::kOcclusion, EdgeKind::kOverrun, EdgeKind::kMaskEdge,
                              EdgeKind::kNoDepth, EdgeKind::kUnknown, EdgeKind::kColourLine})
    for (int k = 0; k < 4; ++k)
    {
      if (candidate.edge_kinds[k] != kind || isRealEdge(kind, uniform_colour)) continue;
      if (kind == EdgeKind::kColourLine)
      {
        lines.push_back(k);
        continue;
      }
      partialAtEdge(k, kind, "");
      return;
    }
  if (const std::optional<std::string> doubt = shapeDoubt(frame, context, *type, candidate))
  {
    if (lines.empty()) candidate.partial_reason = *doubt;
    else partialAtEdge(lines.front(), EdgeKind::kColourLine, "");
    return;
  }
  // A line on a printed face is the box's end where the box across from a
  // real edge can end at it and at no other catalogue size.
  if (const std::optional<std::pair<int, std::string>> unplaced = placeLinesBySize(frame, context, *type, lines,
                                                                                    candidate))
  {
    partialAtEdge(unplaced->first, EdgeKind::kColourLine, unplaced->second);
    return;
  }
  // Last (the most expensive): sides seen below real edges must be as tall
  // as the brick.
  for (int k = 0; k < 4; ++k)
  {
    if (candidate.edge_kinds[k] != EdgeKind::kStepDown && candidate.edge_kinds[k] != EdgeKind::kCrease) continue;
    const SideFaceEvidence side =
        measureSideFace(frame, candidate.corners_m, sideAxis(candidate, context), k, type->height_m, context.up,
                        params_.sides);
    if (judgeSideFace(side, type->height_m, params_.sides) != SideFaceVerdict::kMismatch) continue;
    std::ostringstream text;
    text.precision(3);
    text << "no side face of the catalogue height seen: the side below edge " << k << " is " << side.visible_height_m
         << " m tall, the catalogue's " << type->height_m << " m";
    candidate.partial_reason = text.str();
    return;
  }
  candidate.complete = true;
}
}  // namespace brick_pose
