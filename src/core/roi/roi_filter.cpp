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
#include "brick_pose/common/parallel_for.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/frame/organized_cloud.h"
#include "brick_pose/roi/colour_uniformity.h"
#include "brick_pose/roi/foot_levels.h"
#include "brick_pose/roi/inset_fill.h"
#include "brick_pose/roi/raised_layer.h"
#include "brick_pose/roi/seam_probe.h"
#include "brick_pose/roi/plate_splitter.h"
#include "brick_pose/roi/type_evidence.h"

namespace brick_pose
{
namespace
{
/// A colour-free face that smaller catalogue tops cover this well (all but
/// this share) may be those bricks touching. When seams are seen along
/// nearly every cut (kMinSeenCutShare) the tiles are bricks and may leave
/// more untiled: a pallet stack's boxes merged into one of the large size
/// left 0.105-0.116 with seams along 3 of 3 or 4 cuts, while real single
/// boxes (mOSD) whose print crosses some cuts leave 0.119-0.225 with seams
/// along at most 3 of 5.
constexpr double kMaxUntiledForAlternative = 0.1;
/// A face of one plate colour tiled with every brick laid one way replaces
/// the greedy tiling only if it leaves at most this much more of the face
/// untiled (see tileEachWay): a layout that explains less of the face is
/// no better for seeing more seams.
constexpr double kUntiledSlackOneWay = 0.01;
constexpr double kMaxUntiledWithSeenSeams = 0.15;
/// A wall the camera sees standing at a face's edge, as high as an item
/// resting on the face could be, ends the face unless a catalogue top
/// larger than the face by more than this (m) across the wall could be the
/// face's (see faceMayGoOnBeneathWalls): a strip this narrow under a
/// resting item is within the error of the face's measured size.
constexpr double kMaxCoveredByRestingWallM = 0.005;
constexpr double kMinSeenCutShare = 0.75;
/// A face of one brick's size is cut into smaller bricks along lines only
/// when each is this dark (grey levels below both sides): the rounded edges
/// of touching plates draw lines of 24-30 on the rig in normal light (faces
/// of grey 90-100), while a faint line of 10 is no proof (see
/// test_face_tiling)...
constexpr double kClearSeamLineContrast = 15.0;
/// ... or, on a dimmer face, this share of its level in the grey its lines
/// are read in (faceGreyLevel, FaceGrey): shading scales with the light and
/// with what the face reflects (in low light the rig's seams between reds
/// drew lines of 6-8 on a mean grey of 26, read in the mean of the three
/// channels; read in the reds' own colour both are larger).
constexpr double kClearSeamLineShare = 0.15;
/// The least line a seam can be on any face, however dim (grey levels): the
/// image holds whole levels.
constexpr double kMinSeamLineContrast = 1.0;

std::string describe(const std::string& what, double value, const std::string& rule, double limit)
{
  std::ostringstream text;
  text.precision(3);
  text << what << " " << value << " " << rule << " " << limit;
  return text.str();
}

/// Whether a colour-free segment is a rectangle's worth of its quad: it
/// fills min_fill_ratio of it, or falls short by no more than a ragged rim
/// holds and, inside the rim, is whole but for specks: the jags of a real
/// depth edge reach past 2 px here and there (whole Kinect box tops in mOSD
/// fill 0.955-0.972 of the quad 2 px in), while a corner missing, even one
/// the least-area quad half cuts off, leaves a tenth of it open
/// (`InsetFill.ARaggedRimIsLeftOutAMissingPieceIsNot`).
constexpr double kMinFillInsideRim = 0.95;
bool fillsItsQuad(const BrickCandidate& candidate, const RoiFilterParams& params)
{
  // NaN (not measured) fails the second test.
  return candidate.fill_ratio >= params.min_fill_ratio || candidate.inset_fill_ratio >= kMinFillInsideRim;
}

/// Why one part of a split segment (a tile, a side-by-side cut, a part
/// between depth steps) was dropped, reported over that part's footprint.
RoiRejection partRejection(const Segment& part, const std::string& reason)
{
  return {"part of a split segment: " + reason, part.bounding_box_px, part.area_px};
}

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

/// A line this strong (standard errors of its along-line scatter) where
/// smaller bricks would meet doubts the whole, though the tiler did not cut
/// there. On bench_frontend's rig frames the whole green, blue and box tops
/// scored 0.2-2.6 at their nominal cuts; a row of touching bricks merged
/// into an orange-sized face at 848x480 scored 17 with no cut seen. Two
/// lines of kPairedSeamStrength do too: four red bricks merged into a blue
/// top scored 4.9 and 4.7 at both cuts, and no whole top of 100 frames per
/// class had two above 3. (Measured at one position per line with a line
/// error floor of 1.5 grey levels; the floor is now 0.6 and composed tops
/// are searched across the dimension tolerance, which can only raise the
/// scores: these now doubt more, never less.)
constexpr double kFaintSeamStrength = 5.0;

/// A plain face vouches that no seam crosses it only this bright (mean grey
/// level): the closed seam of two of the rig's red bricks in low light (mean
/// grey 28) is 2 levels deep, under any trace; in normal light (90) seams are
/// 24-47 levels.
constexpr double kMinGreyForSeamToShow = 50.0;
constexpr double kPairedSeamStrength = 4.0;

/// Smaller catalogue tops that make up a larger one: `type`, `along` of
/// them along its length and `across` along its width.
struct Composition
{
  const BrickType* type = nullptr;
  int along = 0, across = 0;
};

/// A smaller catalogue type whose tops, two or more in a grid, make up the
/// top of `whole` within `tolerance_m`; no type when none does.
Composition smallerTypeTiling(const std::vector<BrickType>& types, const BrickType& whole, double tolerance_m)
{
  auto multiple = [&](double total_m, double part_m) {
    const int count = roundToInt(total_m / part_m);
    return count >= 1 && std::abs(total_m - count * part_m) <= tolerance_m ? count : 0;
  };
  for (const BrickType& part : types)
  {
    if (part.length_m * part.width_m >= 0.9 * whole.length_m * whole.width_m) continue;
    for (const bool turned : {false, true})
    {
      const double along_m = turned ? part.width_m : part.length_m;
      const double across_m = turned ? part.length_m : part.width_m;
      const int n = multiple(whole.length_m, along_m), m = multiple(whole.width_m, across_m);
      if (n * m >= 2) return {&part, n, m};
    }
  }
  return {};
}

/// The strongest seam trace (standard errors) along the lines where the
/// smaller tops of `composition` would meet inside a face with corners
/// `c` (c0 -> c1 along its length). Each line is searched up to
/// `tolerance_m` to either side: a face measured a centimetre long at one
/// end puts its middle that far from the seam, beyond scoreSeam's own few
/// pixels of search.
double strongestCompositionSeam(const RgbdFrame& frame, const PlaneFit& plane, const std::array<Eigen::Vector3d, 4>& c,
                                const Composition& composition, double tolerance_m, const EdgeEvidenceParams& params)
{
  constexpr double kStepM = 0.01;  // scoreSeam searches 3 px, 5-8 mm at 1.5 m
  double strongest = 0.0;
  // `part_m`: the smaller top's size across the line; the search stays well
  // inside it, off the face's own edges.
  auto scoreAround = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& across,
                         double part_m) {
    const int steps = static_cast<int>(std::floor(std::min(tolerance_m, 0.4 * part_m) / kStepM));
    for (int step = -steps; step <= steps; ++step)
    {
      const Eigen::Vector3d shift = step * kStepM * across;
      strongest = std::max(strongest, scoreSeam(frame, plane, frame.camera.project(a + shift),
                                                frame.camera.project(b + shift), params)
                                          .strength);
    }
  };
  const double length_m = (c[1] - c[0]).norm(), width_m = (c[3] - c[0]).norm();
  const Eigen::Vector3d along_length = (c[1] - c[0]) / length_m, along_width = (c[3] - c[0]) / width_m;
  for (int k = 1; k < composition.along; ++k)
  {
    const double f = static_cast<double>(k) / composition.along;
    scoreAround(c[0] + f * (c[1] - c[0]), c[3] + f * (c[2] - c[3]), along_length, length_m / composition.along);
  }
  for (int k = 1; k < composition.across; ++k)
  {
    const double f = static_cast<double>(k) / composition.across;
    scoreAround(c[0] + f * (c[3] - c[0]), c[1] + f * (c[2] - c[1]), along_width, width_m / composition.across);
  }
  return strongest;
}

/// Per tile, whether it is plain (see colour_uniformity.h), and so is the
/// whole face (`face`, its uniformity) by its scatter (its seams are
/// outliers, not print): a plain-looking patch of a printed box, a white
/// strip between two prints, is no plate.
std::vector<char> plainTiles(const RgbdFrame& frame, const ColourUniformity& face, const FaceTiling& tiling,
                             const ColourUniformityParams& params)
{
  std::vector<char> plain(tiling.tiles.size(), 0);
  if (face.samples == 0 || face.sigma_grey > params.max_sigma_grey) return plain;
  for (std::size_t k = 0; k < tiling.tiles.size(); ++k)
  {
    const Segment& tile = tiling.tiles[k].segment;
    plain[k] = measureColourUniformity(frame, tile.mask, tile.bounding_box_px, params).uniform;
  }
  return plain;
}

/// The first edge of `tile` cut through its segment without a seam seen
/// along it, or -1.
int firstUnseenCut(const FaceTile& tile)
{
  for (int k = 0; k < 4; ++k)
    if (tile.cut[k] && !tile.seam_seen[k]) return k;
  return -1;
}

/// Tiles of `tiling` with a seam seen along every cut: bricks whose size the
/// image, not the catalogue, drew.
int supportedTileCount(const FaceTiling& tiling)
{
  return static_cast<int>(std::count_if(tiling.tiles.begin(), tiling.tiles.end(),
                                        [](const FaceTile& tile) { return firstUnseenCut(tile) < 0; }));
}

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

/// The direction sides hang from a face: the frame's up for a level face
/// (a narrow top's own normal can be degrees off), else the face's normal.
Eigen::Vector3d sideAxis(const BrickCandidate& candidate, const FrameContext& context)
{
  constexpr double kLevelDeg = 10.0;
  if (context.up.known() && candidate.tilt_from_up_deg <= kLevelDeg) return context.up.up;
  return candidate.normal;
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

bool anyTruncated(const BrickCandidate& candidate)
{
  return std::any_of(candidate.edge_truncated.begin(), candidate.edge_truncated.end(), [](bool cut) { return cut; });
}

/// "edge 2: occlusion boundary" for the first truncated edge.
std::string truncation(const BrickCandidate& candidate)
{
  for (int k = 0; k < 4; ++k)
    if (candidate.edge_truncated[k]) return "edge " + std::to_string(k) + ": " + toString(candidate.edge_kinds[k]);
  return "no edge";
}

std::vector<const BrickType*> typesFor(const BrickCatalogue& catalogue, const std::string& type_name)
{
  std::vector<const BrickType*> types;
  for (const BrickType& type : catalogue.types())
    if (type_name.empty() || type.name == type_name) types.push_back(&type);
  return types;
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
  RoiOutcome outcome;
  BrickCandidate candidate;
  std::optional<std::string> reason = measure(frame, segment, context, cloud_timings, candidate);
  const bool measured = !reason;
  if (!reason) reason = assignType(frame, context, segment, candidate);
  if (!reason)
  {
    // Colour-free: a face of one brick's size may be smaller bricks end to
    // end. Grooves along every cut say it is. A line (or a groove too faint
    // to cut on) where they would meet leaves it unsure: partial. With
    // nothing at all seen there it is taken as one brick.
    FaceTiling alternative;
    if (segment.type_name.empty() && mayHoldTwoBricks(candidate))
    {
      // The smaller types only: the face's own type would tile it whole.
      const BrickType* own = catalogue_.find(candidate.type_name);
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
                    [](EdgeKind kind) { return kind == EdgeKind::kSeam || kind == EdgeKind::kColourLine; });
    if (segment.type_name.empty()) doubtComposedTop(frame, std::nullopt, touches_a_neighbour, candidate);
    outcome.candidates.push_back(std::move(candidate));
    return outcome;
  }
  // Planar and facing up but no single brick: touching bricks merged.
  if (measured)
    if (std::optional<RoiOutcome> split = splitMerged(frame, segment, candidate, context, cloud_timings))
      return std::move(*split);
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
    outcome.rejections.push_back(partRejection(part, *part_reason));
  }
  return outcome;
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

RoiFilter::SeamReading RoiFilter::seamReadingFor(const ColourUniformity& face_uniformity, double face_grey) const
{
  SeamReading reading{params_.edges, params_.tiling};
  if (!face_uniformity.uniform) return reading;
  // A plain face: its lines are seams.
  reading.tiling.confirm_along_lines = params_.confirm_seams_along_lines;
  const double share_of_grey = params_.plain_seam_line_share * face_grey;
  if (share_of_grey < reading.edges.min_line_contrast)
    reading.edges.min_line_contrast = std::max(share_of_grey, kMinSeamLineContrast);
  return reading;
}

FaceTiling RoiFilter::tileBySeenSeams(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                      const std::vector<const BrickType*>& types,
                                      const SeamReading& seams) const
{
  // All types together first (mixed layers); then, when it saw any seam,
  // each type alone, the smallest tops first. Among tilings whose tiles'
  // cuts are seen, the one with most such tiles wins: a row of greens
  // tiled as reds cuts each green where no seam is, and tiled as oranges
  // leaves their seams inside its tiles.
  auto area = [](const BrickType& type) { return type.length_m * type.width_m; };
  std::vector<std::vector<const BrickType*>> type_sets{types};
  std::vector<std::vector<const BrickType*>> single;
  for (const BrickType* type : types) single.push_back({type});
  std::stable_sort(single.begin(), single.end(),
                   [&](const auto& a, const auto& b) { return area(*a.front()) < area(*b.front()); });
  if (types.size() > 1) type_sets.insert(type_sets.end(), single.begin(), single.end());
  // Every tile drawn by seams and the face covered: the tiler, which
  // avoids seams inside its tiles, found the finest tiling there is; and a
  // single type after it can only have fewer, larger tiles.
  auto whollySeen = [](const FaceTiling& tiling) {
    return tiling.tiles.size() >= 2 && supportedTileCount(tiling) == static_cast<int>(tiling.tiles.size()) &&
           tiling.untiled_fraction <= kMaxUntiledForAlternative;
  };
  // Nothing seen along any cut of the mixed tiling (an occluded brick, a
  // row in the dark): no type alone will see more. Most faces tiled here
  // are such, and this keeps them to one tiling.
  // A type alone larger than every brick the mixed tiling drew with seams
  // can only leave those seams inside its tiles.
  auto wanted = [&](std::size_t set, const std::vector<FaceTiling>& made) {
    if (set == 0) return true;
    const FaceTiling& mixed = made.front();
    if (mixed.seen_cuts == 0 || std::any_of(made.begin(), made.end(), whollySeen)) return false;
    double largest_seen_m2 = 0.0;
    for (const FaceTile& tile : mixed.tiles)
      if (firstUnseenCut(tile) < 0)
        if (const BrickType* type = catalogue_.find(tile.type_name)) largest_seen_m2 = std::max(largest_seen_m2, area(*type));
    return largest_seen_m2 == 0.0 || area(*type_sets[set].front()) <= largest_seen_m2 + 1e-9;
  };
  std::vector<FaceTiling> tilings = tileFaceEach(frame, segment, measured, type_sets, params_.dimensions.tolerance_m,
                                                 seams.tiling, seams.edges, wanted);
  // Ranked by tiles drawn by seams less tiles cut where nothing is seen,
  // then by the former, then by the share left untiled.
  FaceTiling* best = nullptr;
  auto rank = [](const FaceTiling& tiling) {
    const int supported = supportedTileCount(tiling);
    const int unsupported = static_cast<int>(tiling.tiles.size()) - supported;
    return std::make_tuple(supported - unsupported, supported, -tiling.untiled_fraction);
  };
  for (FaceTiling& tiling : tilings)
  {
    if (tiling.tiles.size() < 2 || tiling.cuts == 0 || supportedTileCount(tiling) == 0) continue;
    if (!best || rank(tiling) > rank(*best)) best = &tiling;
  }
  if (!best) return FaceTiling();
  cutTileSegments(frame, segment, *best);
  return std::move(*best);
}

FaceTiling RoiFilter::tileEachWay(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                  const std::vector<const BrickType*>& types,
                                  const SeamReading& seams) const
{
  // The greedy tiler lays the tile its seams support best first; where
  // they are faint (a dim frame) its first tiles may lie across a row, and
  // the rest follow them. Every tile laid one way, and every tile laid the
  // other, are the layouts of most rows and layers: one of them is kept
  // when more of its tiles have every cut seen and it leaves no more of the
  // face untiled. Otherwise the greedy tiling stands (mixed layouts).
  std::vector<FaceTiling> tilings = tileFaceEach(
      frame, segment, measured, {types}, params_.dimensions.tolerance_m, seams.tiling, seams.edges,
      [](std::size_t, const std::vector<FaceTiling>&) { return true; },
      {TileOrientation::kEither, TileOrientation::kLongAlongAxis, TileOrientation::kLongAcrossAxis});
  if (tilings.empty()) return FaceTiling();
  const FaceTiling& greedy = tilings.front();
  FaceTiling* best = &tilings.front();
  for (std::size_t k = 1; k < tilings.size(); ++k)
    if (supportedTileCount(tilings[k]) > supportedTileCount(*best) &&
        tilings[k].untiled_fraction <= greedy.untiled_fraction + kUntiledSlackOneWay)
      best = &tilings[k];
  cutTileSegments(frame, segment, *best);
  return std::move(*best);
}

bool RoiFilter::standsUpFromItsSurroundings(const RgbdFrame& frame, const Segment& segment,
                                            const PlaneFit& plane) const
{
  // The quad of a layer that is no rectangle (boxes of mixed sizes, an L
  // of rows) has sides that run over the ground or a taller neighbour
  // beside it, not along the layer's outline: what its sides show says
  // little there. The outline itself does: around a layer the surface
  // falls away; around the floor or a table top, objects stand on it.
  // What an occluder over part of the outline hides, the tiles show: a
  // tile at it is cut off there, and its size does not tell its type.
  const int inner_px = std::max(1, params_.edges.probe_px / 2);
  const int outer_px = inner_px + params_.edges.probe_px;
  return measureOutlineSurroundings(frame, segment, plane, params_.edges.stepM(plane.rms_m), inner_px, outer_px)
      .fallsAwayBesideWalls();
}

bool RoiFilter::oneTileWide(const BrickCandidate& candidate) const
{
  // Two tiles side by side need a whole brick's width and the share of
  // another's the tiler keeps a tile cut off by the border with.
  double narrowest_m = std::numeric_limits<double>::max();
  for (const BrickType& type : catalogue_.types()) narrowest_m = std::min(narrowest_m, type.width_m);
  return candidate.width_m < (1.0 + params_.tiling.min_visible_fraction) * narrowest_m;
}

bool RoiFilter::mayHoldTwoBricks(const BrickCandidate& candidate) const
{
  double smallest_area_m2 = std::numeric_limits<double>::max();
  for (const BrickType& type : catalogue_.types()) smallest_area_m2 = std::min(smallest_area_m2, type.length_m * type.width_m);
  return candidate.length_m * candidate.width_m >= 1.8 * smallest_area_m2;
}

std::optional<RoiOutcome> RoiFilter::tile(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                          const FrameContext& context, bool seams_required,
                                          CloudProcessingTimings* cloud_timings, FaceTiling* tried,
                                          const std::vector<const BrickType*>* only_types) const
{
  const std::vector<const BrickType*> types = only_types ? *only_types : typesFor(catalogue_, segment.type_name);
  if (types.empty()) return std::nullopt;
  const bool typed_by_size = segment.type_name.empty();
  if (typed_by_size && !isRaisedLayer(measured.edge_kinds, clearOfImageBorder(segment, frame, params_.edges.probe_px)) &&
      !standsUpFromItsSurroundings(frame, segment, measured.plane))
    return std::nullopt;
  // Most faces cut off on a pile are one brick partly out of view: where
  // nothing could be a seam across it, tiling would find no cut to keep.
  if (typed_by_size && !seams_required && anyTruncated(measured) && oneTileWide(measured) &&
      !probeSeamsAcross(frame, segment, measured, params_.edges.min_line_contrast, params_.edges.min_groove_m)
           .seam_possible)
    return std::nullopt;
  // Read once: the seam reading and the tiles' plainness both start from it.
  const ColourUniformity face_uniformity =
      measureColourUniformity(frame, segment.mask, segment.bounding_box_px, params_.uniformity);
  // In the grey the seams are read in: their lines scale with it.
  const double face_grey = faceGreyLevel(frame, segment.mask, segment.bounding_box_px);
  const SeamReading seams = seamReadingFor(face_uniformity, face_grey);
  FaceTiling tiling = typed_by_size && !seams_required ? tileBySeenSeams(frame, segment, measured, types, seams)
                      : typed_by_size ? tileFace(frame, segment, measured, types, params_.dimensions.tolerance_m,
                                                 seams.tiling, seams.edges)
                                      : tileEachWay(frame, segment, measured, types, seams);
  if (tried) *tried = tiling;
  if (tiling.tiles.size() < 2) return std::nullopt;
  // Without colour every cut must be seen: a cut made from sizes alone
  // would also make up the type of the bricks it separates. A dark line is
  // a seam only on a plain face (see colour_uniformity.h): print draws lines
  // on boxes, and only a gap between two of them dents the depth, while a
  // real D4xx smooths the groove of a closed seam away (a 4 mm edge rounding
  // leaves about half a millimetre under 3 mm of noise). Where a face of one
  // brick's size is doubted (seams_required), every cut must be grooved, or
  // clearly lined with every tile plain. A face larger than any brick has no
  // single-brick reading: each of its tiles needs its own cuts seen (below),
  // and a tile whose cut is only a line on a printed face stays partial.
  if (typed_by_size && (tiling.cuts == 0 || tiling.seen_cuts == 0)) return std::nullopt;
  const bool cuts_grooved = tiling.cuts > 0 && tiling.grooved_cuts == tiling.cuts;
  const double clear_line = std::min(kClearSeamLineContrast, kClearSeamLineShare * face_grey);
  const bool cuts_lined = tiling.cuts > 0 && tiling.seen_cuts == tiling.cuts &&
                          (!seams_required || tiling.weakest_cut_line >= clear_line);
  if (seams_required && !cuts_grooved && !cuts_lined) return std::nullopt;
  // Read only where it can decide something (it reads every tile).
  const std::vector<char> plain = typed_by_size && (!seams_required || !cuts_grooved)
                                      ? plainTiles(frame, face_uniformity, tiling, params_.uniformity)
                                      : std::vector<char>(tiling.tiles.size(), 0);
  const bool all_plain = std::all_of(plain.begin(), plain.end(), [](char p) { return p != 0; });
  if (seams_required && !cuts_grooved && !all_plain) return std::nullopt;
  // Each tile in its own slots, whichever thread measures it; gathered in
  // the tiling's order.
  const int tile_count = static_cast<int>(tiling.tiles.size());
  std::vector<BrickCandidate> candidates(tiling.tiles.size());
  std::vector<std::optional<std::string>> reasons(tiling.tiles.size());
  std::vector<CloudProcessingTimings> tile_timings(tiling.tiles.size());
  parallelFor(tile_count, params_.worker_threads, [&](int k) {
    // The tiling chose the brick's size: check the part against that type.
    Segment& part = tiling.tiles[k].segment;
    part.type_name = tiling.tiles[k].type_name;
    BrickCandidate& candidate = candidates[k];
    std::optional<std::string>& reason = reasons[k];
    // Without colour, a tile cut where no seam shows is a guess of the
    // tiler's (checked first: it needs no measuring).
    if (typed_by_size && !seams_required)
      if (const int unseen = firstUnseenCut(tiling.tiles[k]); unseen >= 0)
      {
        reason = "cut " + std::to_string(unseen) + " from its neighbour shows no seam (no groove, no line): " +
                 "its size cannot tell its type";
        return;
      }
    reason = measure(frame, part, context, &tile_timings[k], candidate, &seams.edges);
    if (!reason) reason = assignType(frame, context, part, candidate);
    candidate.typed_by_colour = !typed_by_size;  // the tiler's type is a size
    // Without colour, a brick cut off by the border or an occluder could be
    // any longer type: its size does not tell.
    if (!reason && typed_by_size) endAtWalls(frame, context, candidate);
    if (!reason && typed_by_size && anyTruncated(candidate))
      reason = "face is cut by an occluder or the image border (" + truncation(candidate) +
               "): its size cannot tell its type";
    // The tiler's size is one reading of the tile; types sharing that top
    // and boxes lying on a side are its rivals, as for any colour-free face.
    if (!reason && typed_by_size) reason = typeBySize(frame, context, candidate);
    if (!reason) judgeCompleteness(frame, context, !typed_by_size || plain[k], candidate);
    if (!reason && typed_by_size) doubtComposedTop(frame, plain[k] != 0, true, candidate);
  });
  RoiOutcome outcome;
  outcome.candidates.reserve(tiling.tiles.size());  // a growing vector would copy the candidates
  for (int k = 0; k < tile_count; ++k)
  {
    if (cloud_timings) *cloud_timings += tile_timings[k];
    if (reasons[k])
      outcome.rejections.push_back(partRejection(tiling.tiles[k].segment, *reasons[k]));
    else
      outcome.candidates.push_back(std::move(candidates[k]));
  }
  if (tiling.untiled_fraction > 0.2)
    outcome.rejections.push_back({describe("part of a split segment: a share of", tiling.untiled_fraction,
                                           "of it fits no catalogue brick; limit", 0.2),
                                  {}, 0});
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

std::optional<std::string> RoiFilter::assignType(const RgbdFrame& frame, const FrameContext& context,
                                                const Segment& segment, BrickCandidate& candidate) const
{
  const DimensionTolerance& tolerance = params_.dimensions;
  // The box is measured on plane inliers, whose spread grows with depth
  // noise; only thickness beyond that spread says "not a flat face".
  const double noise_spread_m = 6.0 * candidate.plane.rms_m;
  const double thickness_m = candidate.obb.valid ? std::max(0.0, candidate.obb.extents_m.z() - noise_spread_m) : 0.0;
  if (!segment.type_name.empty())
  {
    const BrickType* type = catalogue_.find(segment.type_name);
    if (!type) return "unknown brick type '" + segment.type_name + "'";
    if (auto reason = checkTopFaceDimensions(candidate.length_m, candidate.width_m, thickness_m, *type, tolerance))
      return segment.type_name + ": " + *reason;
    candidate.type_name = type->name;
    candidate.typed_by_colour = true;
    return std::nullopt;
  }

  // Colour-free: only whole faces can be told apart by size (half a blue
  // brick looks like a green one).
  endAtWalls(frame, context, candidate);
  if (anyTruncated(candidate)) return "face is cut by an occluder or the image border (" + truncation(candidate) + ")";
  if (!fillsItsQuad(candidate, params_))
  {
    std::ostringstream text;
    text.precision(3);
    text << "segment fills " << candidate.fill_ratio << " of its quad, less than " << params_.min_fill_ratio;
    if (std::isnan(candidate.inset_fill_ratio))
      text << ", more short than a ragged rim of " << params_.ragged_outline_px << " px holds";
    else
      text << ", and " << candidate.inset_fill_ratio << " of it inside a ragged rim of " << params_.ragged_outline_px
           << " px, less than " << kMinFillInsideRim;
    return text.str();
  }
  if (thickness_m > tolerance.max_thickness_m)
    return describe("thickness", thickness_m, "m exceeds", tolerance.max_thickness_m);
  return typeBySize(frame, context, candidate);
}

std::optional<std::string> RoiFilter::typeBySize(const RgbdFrame& frame, const FrameContext& context,
                                                 BrickCandidate& candidate) const
{
  auto fits = [&](const BrickType& type) {
    return showsTop(type, candidate.length_m, candidate.width_m, params_.classification_tolerance_m);
  };
  std::vector<const BrickType*> fitting;
  double tallest_m = 0.0;
  for (const BrickType& type : catalogue_.types())
    if (fits(type))
    {
      fitting.push_back(&type);
      tallest_m = std::max(tallest_m, type.height_m);
    }
  std::vector<const BrickType*> rivals = fitting;
  for (const BrickType& variant : lying_variants_)
    if (fits(variant))
    {
      rivals.push_back(&variant);
      tallest_m = std::max(tallest_m, variant.height_m);
    }
  // Where the face stands (a support given) narrows its types and, among
  // those left, favours the ones standing exactly at its height.
  const std::optional<StandingHeight> standing =
      rivals.size() > 1 ? standingHeight(frame, context, candidate, rivals) : std::nullopt;
  keepTypesStandingThere(standing, fitting, rivals);
  // Several faces of nearly one size: the sides seen to their foot below
  // the face's real edges say how tall the box is.
  const std::vector<SideFaceEvidence> sides =
      rivals.size() > 1 ? sidesSeenToTheirFoot(frame, context, candidate, tallest_m) : std::vector<SideFaceEvidence>();
  const std::vector<double> standing_misfits_m =
      standing ? standingMisfitsM(fitting, standing->height_m, stack_heights_) : std::vector<double>();
  const BrickType* best = closestType(fitting, candidate.length_m, candidate.width_m, sides, standing_misfits_m);
  if (!best)
  {
    std::ostringstream text;
    text.precision(3);
    text << "face " << candidate.length_m << " x " << candidate.width_m << " m matches no catalogue type";
    return text.str();
  }
  candidate.type_name = best->name;
  const std::vector<const BrickType*> on_support_alone =
      standing ? typesOnSupportAlone(rivals, standing->height_m, standing->levels_m,
                                     params_.height_above_support_tolerance_m)
               : std::vector<const BrickType*>();
  candidate.type_doubt =
      typeDoubt(rivals, *best, candidate.length_m, candidate.width_m, sides, params_.sides, on_support_alone);
  return std::nullopt;
}

std::vector<SideFaceEvidence> RoiFilter::sidesSeenToTheirFoot(const RgbdFrame& frame, const FrameContext& context,
                                                               const BrickCandidate& candidate,
                                                               double tallest_m) const
{
  std::vector<SideFaceEvidence> sides;
  for (int k = 0; k < 4; ++k)
    if (candidate.edge_kinds[k] == EdgeKind::kStepDown || candidate.edge_kinds[k] == EdgeKind::kCrease)
    {
      const SideFaceEvidence side = measureSideFace(frame, candidate.corners_m, sideAxis(candidate, context), k,
                                                    tallest_m, context.up, params_.sides);
      if (side.foot_seen) sides.push_back(side);
    }
  return sides;
}

void RoiFilter::endAtWalls(const RgbdFrame& frame, const FrameContext& context, BrickCandidate& candidate) const
{
  bool any_wall = false;
  for (int k = 0; k < 4; ++k)
  {
    if (!candidate.edge_truncated[k]) continue;
    // Cut off by the border or an occluder: whatever the walls are, the
    // face's size does not tell its type.
    if (std::isnan(candidate.resting_wall_m[k])) return;
    any_wall = true;
  }
  if (!any_wall || faceMayGoOnBeneathWalls(frame, context, candidate)) return;
  for (int k = 0; k < 4; ++k)
    if (candidate.edge_truncated[k])
    {
      candidate.edge_kinds[k] = EdgeKind::kStepUp;
      candidate.edge_truncated[k] = false;
    }
}

bool RoiFilter::faceMayGoOnBeneathWalls(const RgbdFrame& frame, const FrameContext& context,
                                        const BrickCandidate& candidate) const
{
  // Edges 0 and 2 run along the face's length: a wall there may hide more
  // of its width; a wall on an end (1, 3) more of its length. A top larger
  // by less than kMaxCoveredByRestingWallM is the face measured short.
  auto walled = [&](int k) { return candidate.edge_truncated[k] && !std::isnan(candidate.resting_wall_m[k]); };
  const bool may_be_wider = walled(0) || walled(2), may_be_longer = walled(1) || walled(3);
  const double hidden_m = kMaxCoveredByRestingWallM;
  const double tolerance_m = params_.classification_tolerance_m;
  auto extends = [&](double along_m, double across_m) {
    const bool length_fits = may_be_longer ? along_m >= candidate.length_m + hidden_m
                                           : std::abs(along_m - candidate.length_m) <= tolerance_m;
    const bool width_fits = may_be_wider ? across_m >= candidate.width_m + hidden_m
                                         : std::abs(across_m - candidate.width_m) <= tolerance_m;
    return length_fits && width_fits;
  };
  std::vector<const BrickType*> larger, own;
  auto consider = [&](const BrickType& type) {
    if (extends(type.length_m, type.width_m) || extends(type.width_m, type.length_m)) larger.push_back(&type);
    if (showsTop(type, candidate.length_m, candidate.width_m, tolerance_m)) own.push_back(&type);
  };
  for (const BrickType& type : catalogue_.types()) consider(type);
  for (const BrickType& variant : lying_variants_) consider(variant);
  // No catalogue top is larger that way: nothing rests on the face, which
  // ends at the walls.
  if (larger.empty()) return false;
  // Only the face's height above a given support rules those tops out.
  const std::optional<StandingHeight> standing = standingHeight(frame, context, candidate, own);
  if (!standing) return true;
  return !typesStandingAt(larger, standing->height_m, standing->levels_m, stack_heights_,
                          params_.height_above_support_tolerance_m)
              .empty();
}

std::optional<RoiFilter::StandingHeight> RoiFilter::standingHeight(const RgbdFrame& frame,
                                                                   const FrameContext& context,
                                                                   const BrickCandidate& candidate,
                                                                   const std::vector<const BrickType*>& shown) const
{
  const double tolerance_m = params_.height_above_support_tolerance_m;
  if (!(tolerance_m > 0.0) || !context.up.support_given) return std::nullopt;
  const double height_m = context.up.heightAboveSupport(candidate.centroid_m);
  // None of the tops it shows could stand there: the face stands on
  // something else (a plinth, the given plane is the floor under a
  // pallet), and its height says nothing.
  if (typesStandingAt(shown, height_m, {}, stack_heights_, tolerance_m).empty()) return std::nullopt;
  // A deck or a plinth seen around the face's foot is one more place it
  // may stand: it may only widen what the face can be.
  return StandingHeight{height_m, levelsAroundFoot(frame, candidate.mask, candidate.bounding_box_px,
                                                   candidate.plane, context.up, tolerance_m)};
}

void RoiFilter::keepTypesStandingThere(const std::optional<StandingHeight>& height,
                                       std::vector<const BrickType*>& fitting,
                                       std::vector<const BrickType*>& rivals) const
{
  if (rivals.size() < 2 || !height) return;
  const std::vector<const BrickType*> standing = typesStandingAt(rivals, height->height_m, height->levels_m,
                                                                 stack_heights_,
                                                                 params_.height_above_support_tolerance_m);
  if (standing.size() == rivals.size()) return;
  std::vector<const BrickType*> fitting_standing;
  for (const BrickType* type : fitting)
    if (std::find(standing.begin(), standing.end(), type) != standing.end()) fitting_standing.push_back(type);
  // No catalogue type could stand there but a box lying on a side could:
  // the types stay, and the lying box doubts them.
  if (!fitting_standing.empty()) fitting = std::move(fitting_standing);
  rivals = standing;
  for (const BrickType* type : fitting)
    if (std::find(rivals.begin(), rivals.end(), type) == rivals.end()) rivals.push_back(type);
}

void RoiFilter::doubtComposedTop(const RgbdFrame& frame, std::optional<bool> plain, bool in_layer,
                                 BrickCandidate& candidate) const
{
  if (!candidate.complete) return;
  const BrickType* type = catalogue_.find(candidate.type_name);
  if (!type) return;
  const Composition composition = smallerTypeTiling(catalogue_.types(), *type, params_.dimensions.tolerance_m);
  if (!composition.type) return;
  const std::string printed = "on a printed face their seam need not show";
  std::string why;
  // In a layer, a face already known printed is doubted whatever lines it
  // shows (the search along the meeting lines is spared); otherwise a trace
  // there doubts it, and without one a face standing alone is one box.
  if (in_layer && plain && !*plain)
    why = printed;
  else if (strongestCompositionSeam(frame, candidate.plane, candidate.corners_m, composition,
                                    params_.dimensions.tolerance_m, params_.edges) >= kFaintSeamStrength)
    why = "a line (or a trace of one) crosses it where they would meet";
  else if (!in_layer)
    return;
  else if (!(plain ? *plain
                    : measureColourUniformity(frame, candidate.mask, candidate.bounding_box_px, params_.uniformity)
                          .uniform))
    why = printed;
  else
  {
    // On a plain face the seam shows, where there is light enough for it to.
    const double grey = meanGreyLevel(frame, candidate.mask, candidate.bounding_box_px);
    if (grey >= kMinGreyForSeamToShow) return;
    why = describe("the face is too dark for their seam to show (mean grey", grey, "levels, need",
                   kMinGreyForSeamToShow) +
          ")";
  }
  candidate.complete = false;
  candidate.partial_reason = "its top is also " + composition.type->name + " tops touching, and " + why;
  // Its type is in doubt: one brick of this type, or several smaller ones.
  candidate.type_doubt = candidate.partial_reason;
}

void RoiFilter::judgeCompleteness(const RgbdFrame& frame, const FrameContext& context, bool uniform_colour,
                                  BrickCandidate& candidate) const
{
  candidate.complete = false;
  candidate.partial_reason.clear();
  const BrickType* type = catalogue_.find(candidate.type_name);
  if (!type)
  {
    candidate.partial_reason = "unknown brick type '" + candidate.type_name + "'";
    return;
  }
  // Edges that hide where the brick ends say the most: the border and
  // occluders first, then planes that continue, then missing depth.
  for (const EdgeKind kind : {EdgeKind::kImageBorder, EdgeKind::kOcclusion, EdgeKind::kOverrun, EdgeKind::kMaskEdge,
                              EdgeKind::kNoDepth, EdgeKind::kUnknown, EdgeKind::kColourLine})
    for (int k = 0; k < 4; ++k)
      if (candidate.edge_kinds[k] == kind && !isRealEdge(kind, uniform_colour))
      {
        candidate.partial_reason = edgeReason(k, kind);
        return;
      }
  // The face goes on, on its own plane, where the segment does not: a mask
  // over part of a printed top, whose quad may still have the catalogue's
  // size. (Where something nearer covers the quad, the brick's extent is
  // still known from its ends: covered, not partial.)
  const double uncovered = unsegmentedCoplanarFraction(frame, candidate, params_.edges.min_step_m);
  if (uncovered > 1.0 - params_.min_fill_ratio)
  {
    candidate.partial_reason =
        describe("the face continues on its plane outside the segment over", uncovered, "of its quad; limit",
                 1.0 - params_.min_fill_ratio);
    return;
  }
  const double tolerance_m = params_.dimensions.tolerance_m;
  if (std::abs(candidate.length_m - type->length_m) > tolerance_m ||
      std::abs(candidate.width_m - type->width_m) > tolerance_m)
  {
    std::ostringstream text;
    text.precision(3);
    text << "visible size " << candidate.length_m << " x " << candidate.width_m << " m is not the catalogue's "
         << type->length_m << " x " << type->width_m << " m";
    // A box lying on a side shows such a face up: the doubt names it.
    if (!candidate.type_doubt.empty()) text << "; " << candidate.type_doubt;
    candidate.partial_reason = text.str();
    return;
  }
  if (!context.up.known())
  {
    candidate.partial_reason = "up direction unknown: a top face cannot be told from a side face";
    return;
  }
  if (!candidate.type_doubt.empty())
  {
    candidate.partial_reason = candidate.type_doubt;
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
