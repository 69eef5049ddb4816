// RoiFilter, part 2 of 3: splitting a merged colour-free or one-colour face
// into bricks by tiling it with catalogue tops (face_tiling.h) and checking
// each tile. roi_filter.cpp measures faces; roi_filter_typing.cpp types them.

#include "brick_pose/roi/roi_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "brick_pose/common/parallel_for.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/roi/colour_uniformity.h"
#include "brick_pose/roi/foot_levels.h"
#include "brick_pose/roi/raised_layer.h"
#include "brick_pose/roi/seam_probe.h"
#include "brick_pose/roi/size_placed_edge.h"

#include "roi_filter_internal.h"

namespace brick_pose
{
using roi_internal::addTypeDoubt;
using roi_internal::typesFor;
using roi_internal::describe;
using roi_internal::partRejection;
using roi_internal::anyTruncated;
using roi_internal::kMaxUntiledForAlternative;

namespace
{
/// A face of one plate colour tiled with every brick laid one way replaces
/// the greedy tiling only if it leaves at most this much more of the face
/// untiled (see tileEachWay): a layout that explains less of the face is
/// no better for seeing more seams.
constexpr double kUntiledSlackOneWay = 0.01;

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

/// Where a probed seam or end may lie off the tiler's cut: a bin or two of
/// the probe (a pixel each) and the tiler's cells (4 mm).
constexpr double kProbedEndSlackM = 0.01;
/// Two tiles' edges along one cut lie this close (m): the tiler cut both
/// along one line, each refitted to its own pixels since.
constexpr double kMeetingLineM = 0.02;

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

/// Either side of a cut, the band whose colour says whether its line is
/// print (m on the face, the line itself left out): a label or a tape
/// stripe that draws a line also marks the cardboard beside it.
constexpr double kCutBandM = 0.05;
/// The line's own pixels left out of the band (px either side): the seam's
/// shading, the colour's 1-2 px misregistration and the tiler's cut a
/// pixel or two off the line.
constexpr int kCutLineHalfPx = 4;
/// A band narrower than this (px either side) holds too few blocks to read.
constexpr int kMinCutBandPx = 14;

/// Whether the face (`inner_face`: `face`'s mask withoutRim, as
/// measureColourUniformity reads a face; the bands cut from it keep their
/// own sides, since a band a few blocks wide seen at a slant would keep no
/// whole block) around each cut of `tile` is plain (see
/// colour_uniformity.h) within kCutBandM of it: a clear line along a cut
/// there is no print, whatever print lies further off on the tiles.
bool cutsInPlainBands(const RgbdFrame& frame, const Segment& face, const cv::Mat& inner_face, const FaceTile& tile,
                      const ColourUniformityParams& params)
{
  const cv::Rect& box = face.bounding_box_px;
  ColourUniformityParams band_params = params;
  band_params.rim_px = 0;  // left out of inner_face already
  bool any_cut = false;
  for (int k = 0; k < 4; ++k)
  {
    if (!tile.cut[k]) continue;
    any_cut = true;
    const Eigen::Vector3d& a_m = tile.corners_m[k];
    const Eigen::Vector3d& b_m = tile.corners_m[(k + 1) % 4];
    const double depth_m = 0.5 * (a_m.z() + b_m.z());
    if (!(depth_m > 0.0)) return false;
    const int band_px =
        std::max(kMinCutBandPx, roundToInt(kCutBandM * frame.camera.fx_px / depth_m));
    const Eigen::Vector2d a = frame.camera.project(a_m), b = frame.camera.project(b_m);
    const cv::Point a_px(roundToInt(a.x()) - box.x, roundToInt(a.y()) - box.y);
    const cv::Point b_px(roundToInt(b.x()) - box.x, roundToInt(b.y()) - box.y);
    cv::Mat band = cv::Mat::zeros(box.size(), CV_8UC1);
    cv::line(band, a_px, b_px, cv::Scalar(255), 2 * band_px + 1);
    cv::line(band, a_px, b_px, cv::Scalar(0), 2 * kCutLineHalfPx + 1);
    band &= inner_face;
    if (!measureColourUniformity(frame, band, box, band_params).uniform) return false;
  }
  return any_cut;
}

/// Whether every edge of `face` is seen in depth (a step, a crease, a
/// groove, a wall's foot): on such a face the only lines a tiling can cut
/// along are its cuts.
bool edgesSeenInDepth(const BrickCandidate& face)
{
  return std::all_of(face.edge_kinds.begin(), face.edge_kinds.end(), [](EdgeKind kind) {
    return kind != EdgeKind::kSizePlacedLine && isRealEdge(kind, false);
  });
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

/// Each of some types on its bottom, then lying on a side or standing on
/// an end (lyingVariants), and which type each pose is of.
struct TypePoses
{
  std::vector<const BrickType*> types;
  std::vector<BrickType> poses;
  std::vector<std::size_t> type_of;  ///< per pose, its type's index in `types`

  std::vector<const BrickType*> pointers() const
  {
    std::vector<const BrickType*> result;
    for (const BrickType& pose : poses) result.push_back(&pose);
    return result;
  }
  /// The types of `of` (poses of these), each once, in the types' order.
  std::vector<const BrickType*> typesOf(const std::vector<const BrickType*>& of) const
  {
    std::vector<char> kept(types.size(), 0);
    for (const BrickType* pose : of) kept[type_of[static_cast<std::size_t>(pose - poses.data())]] = 1;
    std::vector<const BrickType*> result;
    for (std::size_t t = 0; t < types.size(); ++t)
      if (kept[t]) result.push_back(types[t]);
    return result;
  }
};

TypePoses posesOf(const std::vector<const BrickType*>& types)
{
  TypePoses result;
  result.types = types;
  for (std::size_t t = 0; t < types.size(); ++t)
  {
    result.poses.push_back(*types[t]);
    for (BrickType& variant : lyingVariants({*types[t]})) result.poses.push_back(std::move(variant));
    result.type_of.resize(result.poses.size(), t);
  }
  return result;
}
}  // namespace

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
                                      const std::vector<const BrickType*>& types, const SeamReading& seams,
                                      bool sizes_place_cuts) const
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
    if (tiling.tiles.size() < 2 || tiling.cuts == 0) continue;
    if (supportedTileCount(tiling) == 0 && !sizes_place_cuts) continue;
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

bool RoiFilter::mayCutAWholeBrick(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& strip,
                                  const std::vector<const BrickType*>& types) const
{
  const SeamProbe probe =
      probeSeamsAcross(frame, segment, strip, params_.edges.min_line_contrast, params_.edges.min_groove_m);
  if (!probe.seam_possible) return false;
  // The strip's ends are seen unless cut off; one cut off at walls may yet
  // end there (endAtWalls).
  auto seen = [&](int k) { return !strip.edge_truncated[k] || !std::isnan(strip.resting_wall_m[k]); };
  std::vector<double> lengths_m;
  for (const BrickType* type : types)
  {
    lengths_m.push_back(type->length_m);
    lengths_m.push_back(type->width_m);
  }
  // A tile is typed by its size within classification_tolerance_m; the
  // probe's bins and the tiler's cells add a few millimetres.
  return seamsMayBoundABrick(probe, {{seen(probe.end_edges[0]), seen(probe.end_edges[1])}}, lengths_m,
                             params_.classification_tolerance_m + kProbedEndSlackM);
}

bool RoiFilter::mayShowASeamAcross(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& face) const
{
  // Smaller tops in a face one brick wide meet along cuts across its whole
  // width, where the probe's bins average: a seam there, or a trace of one
  // faint enough only to doubt the face, dips them too. Where none dips,
  // the smaller tops' tiling finds no cut to keep and no trace to doubt by
  // (none of 93 such faces on the rig's 100 frames per class at three
  // resolutions). The lines where one smaller type would meet are still
  // searched (doubtComposedTop).
  return !oneTileWide(face) ||
         probeSeamsAcross(frame, segment, face, params_.edges.min_line_contrast, params_.edges.min_groove_m)
             .seam_possible;
}

void RoiFilter::placeLinesAcrossTiles(const RgbdFrame& frame, const FrameContext& context,
                                      const std::vector<char>& plain,
                                      const std::vector<std::optional<std::string>>& reasons,
                                      std::vector<BrickCandidate>& tiles) const
{
  const auto placedAcross = [&](std::size_t k, int edge) {
    for (std::size_t other = 0; other < tiles.size(); ++other)
    {
      if (other == k || reasons[other]) continue;
      for (int other_edge = 0; other_edge < 4; ++other_edge)
        if (tiles[other].edge_kinds[other_edge] == EdgeKind::kSizePlacedLine &&
            meetAlongEdge(tiles[k], edge, tiles[other], other_edge, kMeetingLineM))
          return true;
    }
    return false;
  };
  // Each round places at least one more line, or stops.
  for (bool placed_more = true; placed_more;)
  {
    placed_more = false;
    for (std::size_t k = 0; k < tiles.size(); ++k)
    {
      BrickCandidate& tile = tiles[k];
      if (reasons[k] || tile.complete || plain[k]) continue;
      bool took = false;
      for (int edge = 0; edge < 4; ++edge)
        if (tile.edge_kinds[edge] == EdgeKind::kColourLine && placedAcross(k, edge))
        {
          tile.edge_kinds[edge] = EdgeKind::kSizePlacedLine;
          took = true;
        }
      if (!took) continue;
      placed_more = true;
      judgeCompleteness(frame, context, false, tile);
      doubtComposedTop(frame, context, false, true, tile);
    }
  }
}

std::optional<std::vector<const BrickType*>> RoiFilter::posesStandingMostExactly(
    const RgbdFrame& frame, const FrameContext& context, const BrickCandidate& face,
    const std::vector<const BrickType*>& shown) const
{
  if (!heightTellsTypes(context)) return std::nullopt;
  const double tolerance_m = params_.height_above_support_tolerance_m;
  const double height_m = context.up.heightAboveSupport(face.centroid_m);
  std::vector<const BrickType*> standing = typesStandingAt(shown, height_m, {}, stack_heights_, tolerance_m);
  if (standing.empty()) return std::nullopt;
  // The poses standing there most exactly, as closestType weighs them.
  std::vector<double> misfits_m = standingMisfitsM(standing, height_m, stack_heights_);
  double least_m = *std::min_element(misfits_m.begin(), misfits_m.end());
  // A level around the foot (a deck, a plinth) is one more place to stand,
  // but a pose standing only there misfits the support's stacks by more
  // than the tolerance: read only where that could still be exact.
  if (least_m + kTypeMarginM >= tolerance_m && standing.size() < shown.size())
  {
    standing = typesStandingAt(
        shown, height_m, levelsAroundFoot(frame, face.mask, face.bounding_box_px, face.plane, context.up, tolerance_m),
        stack_heights_, tolerance_m);
    misfits_m = standingMisfitsM(standing, height_m, stack_heights_);
    least_m = *std::min_element(misfits_m.begin(), misfits_m.end());
  }
  std::vector<const BrickType*> exact;
  for (std::size_t i = 0; i < standing.size(); ++i)
    if (misfits_m[i] <= least_m + kTypeMarginM) exact.push_back(standing[i]);
  return exact;
}

RoiFilter::TypesAtHeight RoiFilter::typesStandingWhereTheFaceIs(const RgbdFrame& frame, const FrameContext& context,
                                                                const BrickCandidate& face,
                                                                const std::vector<const BrickType*>& types) const
{
  // Every brick of a merged face stands where the face is: two box_small
  // side by side 0.15 m above the floor make a box_large's top, but no
  // box_large (0.25 m tall) has its top there, on its bottom, a side or an
  // end. Without a support, or where none of the types could stand (a
  // plinth under the pile), all stay.
  if (!heightTellsTypes(context)) return {types, false};
  const TypePoses poses = posesOf(types);
  const std::optional<std::vector<const BrickType*>> exact =
      posesStandingMostExactly(frame, context, face, poses.pointers());
  if (!exact) return {types, false};
  // Types standing there clearly less exactly than another (a box_flat
  // 0.25 m up needs a box lying on a side beneath, 2 cm off, where a
  // box_large stands on the ground) are no tiles: two such tops side by
  // side make the exact one's. (A box lying exactly there is a tile too:
  // its face may be near its top's size.)
  TypesAtHeight result;
  result.types = poses.typesOf(*exact);
  // The exact poses all show one top, a type's on its bottom (the tiler
  // lays no lying box's face): a cut the tiler made at that size is placed.
  const BrickType& top = *exact->front();
  auto showsThatTop = [&](const BrickType* pose) {
    return showsTop(*pose, top.length_m, top.width_m, params_.dimensions.tolerance_m);
  };
  result.one_top_size = std::all_of(exact->begin(), exact->end(), showsThatTop) &&
                        std::any_of(result.types.begin(), result.types.end(), showsThatTop);
  return result;
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
  const bool typed_by_size = segment.type_name.empty();
  const std::vector<const BrickType*> all_types = only_types ? *only_types : typesFor(catalogue_, segment.type_name);
  if (all_types.empty()) return std::nullopt;
  if (typed_by_size && !isRaisedLayer(measured.edge_kinds, clearOfImageBorder(segment, frame, params_.edges.probe_px)) &&
      !standsUpFromItsSurroundings(frame, segment, measured.plane))
    return std::nullopt;
  // Most faces cut off on a pile are one brick partly out of view: where
  // nothing could be a seam across it, or no brick could lie between its
  // seen ends and possible seams, tiling would keep nothing.
  if (typed_by_size && !seams_required && anyTruncated(measured) && oneTileWide(measured) &&
      !mayCutAWholeBrick(frame, segment, measured, all_types))
    return std::nullopt;
  const TypesAtHeight at_height = typed_by_size ? typesStandingWhereTheFaceIs(frame, context, measured, all_types)
                                                : TypesAtHeight{all_types, false};
  const std::vector<const BrickType*>& types = at_height.types;
  // Read once: the seam reading and the tiles' plainness both start from it.
  const ColourUniformity face_uniformity =
      measureColourUniformity(frame, segment.mask, segment.bounding_box_px, params_.uniformity);
  // In the grey the seams are read in: their lines scale with it.
  const double face_grey = faceGreyLevel(frame, segment.mask, segment.bounding_box_px);
  const SeamReading seams = seamReadingFor(face_uniformity, face_grey);
  FaceTiling tiling = typed_by_size && !seams_required
                          ? tileBySeenSeams(frame, segment, measured, types, seams, at_height.one_top_size)
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
  // Where the face's height leaves one top size, that size places the cuts:
  // tiles cut where nothing is seen are published in doubt (below).
  if (typed_by_size && (tiling.cuts == 0 || (tiling.seen_cuts == 0 && !at_height.one_top_size))) return std::nullopt;
  const bool cuts_grooved = tiling.cuts > 0 && tiling.grooved_cuts == tiling.cuts;
  const double clear_line = std::min(kClearSeamLineContrast, kClearSeamLineShare * face_grey);
  const bool cuts_lined = tiling.cuts > 0 && tiling.seen_cuts == tiling.cuts &&
                          (!seams_required || tiling.weakest_cut_line >= clear_line);
  if (seams_required && !cuts_grooved && !cuts_lined) return std::nullopt;
  // Read only where it can decide something (it reads every tile).
  std::vector<char> plain = typed_by_size && (!seams_required || !cuts_grooved)
                                ? plainTiles(frame, face_uniformity, tiling, params_.uniformity)
                                : std::vector<char>(tiling.tiles.size(), 0);
  // A face of one brick's size whose edges are all seen in depth has no
  // lines but its cuts. Where each cut is clearly lined, a printed tile
  // counts as plain when the cardboard along its cuts is: the line is then
  // no print. (Two labelled box_small side by side on a stack make a
  // box_large's top.)
  if (seams_required && !cuts_grooved && cuts_lined && edgesSeenInDepth(measured))
  {
    const cv::Mat inner_face = withoutRim(segment.mask, params_.uniformity.rim_px);
    for (std::size_t k = 0; k < plain.size(); ++k)
      if (!plain[k]) plain[k] = cutsInPlainBands(frame, segment, inner_face, tiling.tiles[k], params_.uniformity);
  }
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
    const int unseen = typed_by_size && !seams_required ? firstUnseenCut(tiling.tiles[k]) : -1;
    if (unseen >= 0 && !at_height.one_top_size)
    {
      reason = "cut " + std::to_string(unseen) + " from its neighbour shows no seam (no groove, no line): " +
               "its size cannot tell its type";
      return;
    }
    reason = measure(frame, part, context, &tile_timings[k], candidate, &seams.edges);
    if (!reason) reason = assignType(frame, context, part, candidate);
    candidate.typed_by_colour = !typed_by_size;  // the tiler's type is a size
    // Without colour, a brick cut off by the border or an occluder could be
    // any longer type: its size does not tell, and its visible part's type
    // is a doubt (typeCutOffFace).
    if (!reason && typed_by_size) endAtWalls(frame, context, candidate);
    if (!reason && typed_by_size && anyTruncated(candidate))
    {
      reason = typeCutOffFace(frame, context, candidate);
    }
    else if (!reason && typed_by_size)
    {
      // The tiler's size is one reading of the tile; types sharing that top
      // and boxes lying on a side are its rivals, as for any colour-free face.
      reason = typeBySize(frame, context, candidate);
    }
    if (!reason && unseen >= 0)
    {
      // Where it was cut, the face's height placed the cut: the catalogue
      // has one top there. A doubt, so the tile is never complete.
      const std::string doubt = "cut " + std::to_string(unseen) +
                                " from its neighbour shows no seam: its size is the one top standing at its height";
      addTypeDoubt(candidate, doubt);
    }
    if (!reason) judgeCompleteness(frame, context, !typed_by_size || plain[k], candidate);
    if (!reason && typed_by_size) doubtComposedTop(frame, context, plain[k] != 0, true, candidate);
  });
  if (typed_by_size) placeLinesAcrossTiles(frame, context, plain, reasons, candidates);
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
}  // namespace brick_pose
