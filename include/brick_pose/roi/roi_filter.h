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
#include "brick_pose/roi/colour_uniformity.h"
#include "brick_pose/roi/edge_evidence.h"
#include "brick_pose/roi/face_tiling.h"
#include "brick_pose/roi/side_faces.h"
#include "brick_pose/roi/type_evidence.h"
#include "brick_pose/roi/up_direction.h"
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
  /// A step up at an edge to a wall standing there (EdgeKind::kStepUp: one
  /// height all along the edge, hiding at most edges.max_hidden_by_wall_m
  /// of the face) ends the face only when no catalogue item, lying on its
  /// bottom, a side or an end, alone or on another, could rest on the face
  /// and rise that high: within this margin (m) of such a height it may be
  /// resting there, and the face may go on beneath it (an occlusion). The
  /// pile is assumed to hold catalogue items: a foreign object resting
  /// along a whole edge, of a height no item has, would pass.
  double resting_height_margin_m = 0.015;
  /// Colour-free segments must also fill their quad this well: pieces of
  /// the ground or of merged faces are not rectangles.
  double min_fill_ratio = 0.85;
  /// ... or fall short by no more than a rim this deep along the quad's
  /// sides holds, and fill the quad inside the rim but for specks: how deep
  /// a sensor's ragged depth boundary may eat into a face (see inset_fill.h).
  double ragged_outline_px = 2.0;
  /// A complete colour-free face (its type known) is placed at its
  /// catalogue size: the excess of its measured size is taken off the edges
  /// its depth bounds, which D4xx depth carries a few pixels too far (see
  /// catalogue_size_placement.h). Its centre, corners and T1/T2 move; its
  /// measured length and width stay.
  bool place_on_catalogue_size = true;
  /// "Up" (unit, camera frame, e.g. from tf through the nodelet's
  /// up_frame). When zero, the front end estimates it per frame (see
  /// up_direction.h). Faces whose normal is more than max_tilt_deg from up
  /// are not top faces and are dropped.
  Eigen::Vector3d up_direction = Eigen::Vector3d::Zero();
  /// The plane the pile stands on (camera frame, (n, d) with n . p + d = 0
  /// and n pointing up; e.g. from tf through the nodelet's support_frame).
  /// Zero: not given. Only a given support tells types apart by a face's
  /// height above it (height_above_support_tolerance_m): an estimated one
  /// may be the top of a layer filling the view.
  Eigen::Vector4d support_plane = Eigen::Vector4d::Zero();
  double max_tilt_deg = 30.0;
  /// What lies beyond each edge of a face (complete needs four real edges).
  EdgeEvidenceParams edges;
  /// Cutting merged faces of touching bricks by tiling them with catalogue sizes.
  FaceTilingParams tiling;
  /// Side faces below the edges must have the catalogue height.
  SideFaceParams sides;
  /// Colour-free: whether a tile of a merged face is of one plain colour,
  /// so that a line along its cut is a seam (see colour_uniformity.h).
  ColourUniformityParams uniformity;
  /// On a plain face (see colour_uniformity.h) darker than grey level
  /// edges.min_line_contrast / plain_seam_line_share (100 by default: a
  /// face in low light), a line is a seam, for the tiler and for the edges
  /// of its tiles, from this share of the face's level in the grey its
  /// lines are read in (faceGreyLevel: weighted by its own colour)
  /// (and at least one level) instead of from edges.min_line_contrast: a
  /// seam's shading is a share of the light the face sends back (its
  /// colour, the lighting, the camera's exposure), so a dark face's seams
  /// are as faint in proportion. Printed faces keep the absolute floor
  /// (their lines are print). 0 keeps edges.min_line_contrast everywhere.
  double plain_seam_line_share = 0.06;
  /// On a printed face a colour line ends the box where the catalogue's
  /// sizes place it (size_placed_edge.h), and only on a face whose length
  /// and width are both within this of its type's: the premise is that a
  /// catalogue box lies there, and a face the tolerance's 3 cm off may be
  /// part of a box the catalogue lacks (a real tea box's top, cut into
  /// smaller ones along its print). 0: lines on printed faces never end one.
  double size_placed_line_tolerance_m = 0.015;
  /// On a plain face, a cut seen but too short to confirm alone is
  /// confirmed with the cuts continuing it on one line (see
  /// FaceTilingParams::confirm_along_lines).
  bool confirm_seams_along_lines = true;
  /// Colour-free: a face's height above the given supporting plane
  /// (support_plane, or the frame's support from tf) rules out the types
  /// that could not stand there, on the support or on a stack of catalogue
  /// items, within this distance (m). Boxes that share a top but not a
  /// height (a flat and a tall box) are told apart by it where no side face
  /// shows. It trusts the given plane to be what the pile stands on (a
  /// pallet's deck, not the floor under it); 0 switches it off.
  double height_above_support_tolerance_m = 0.025;
  PlaneFitParams plane;
  QuadFitParams quad;
  /// The bricks a merged face is cut into are measured on this many threads
  /// (1: in the caller's). A row of touching bricks is one segment, so the
  /// front end's threads over segments leave one core idle while its dozen
  /// bricks are measured. Not a parameter of its own: the front end passes
  /// front_end_threads.
  int worker_threads = 1;

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

/// Why a segment, or one part of it, was dropped.
struct RoiRejection
{
  std::string reason;
  /// The part's footprint (a tile, a side-by-side cut, a part between
  /// depth steps); empty when the reason is about the whole segment.
  cv::Rect part_box_px;
  int part_area_px = 0;
};

/// Everything one segment turned into (several candidates when it was split).
struct RoiOutcome
{
  std::vector<BrickCandidate> candidates;
  std::vector<RoiRejection> rejections;
};

/// What the front end decided about a whole frame before filtering its
/// segments one by one.
struct FrameContext
{
  UpDirection up;
};

class RoiFilter
{
public:
  /// Throws ConfigError for a bad parameter.
  RoiFilter(const BrickCatalogue& catalogue, const RoiFilterParams& params, const CloudProcessorParams& cloud_params);

  /// Filters one segment. HSV segments are checked against their type;
  /// colour-free ones are classified by their dimensions. `context` says
  /// which way is up; `cloud_timings` (optional) accumulates the
  /// cloud-processing time.
  RoiResult filter(const RgbdFrame& frame, const Segment& segment, const FrameContext& context,
                   CloudProcessingTimings* cloud_timings = nullptr) const;
  /// The same with up from RoiFilterParams::up_direction (unknown when zero).
  RoiResult filter(const RgbdFrame& frame, const Segment& segment, CloudProcessingTimings* cloud_timings = nullptr) const;

  /// Like filter(), but a planar segment larger than one brick (touching
  /// bricks of one colour and height merged into one face) is cut into
  /// bricks by tiling it with catalogue sizes along the seams the image
  /// shows (see face_tiling.h); a colour-free face of one brick's size whose
  /// halves are split by seen seams is cut too; a segment that is not planar
  /// is split where its depth steps (see splitAtDepthSteps()).
  RoiOutcome filterSplitting(const RgbdFrame& frame, const Segment& segment, const FrameContext& context,
                             CloudProcessingTimings* cloud_timings = nullptr) const;
  RoiOutcome filterSplitting(const RgbdFrame& frame, const Segment& segment,
                             CloudProcessingTimings* cloud_timings = nullptr) const;

  /// The context filter() uses without one: up from the parameters.
  FrameContext defaultContext() const;

  const RoiFilterParams& params() const { return params_; }

private:
  /// filterSplitting() before complete faces are placed at their catalogue size.
  RoiOutcome filterSplittingAsMeasured(const RgbdFrame& frame, const Segment& segment, const FrameContext& context,
                                       CloudProcessingTimings* cloud_timings) const;
  /// place_on_catalogue_size for one candidate (complete and colour-free
  /// only; others are left as they are).
  void placeOnCatalogueSize(const RgbdFrame& frame, BrickCandidate& candidate) const;
  /// How far inside each depth-bounded edge of `candidate` the colour image
  /// shows the face end (m on its plane; stepEdgeInsetPx), where the edge
  /// across from it is depth-bounded too; NaN elsewhere or where colour
  /// cannot tell.
  std::array<double, 4> colourInsetsM(const RgbdFrame& frame, const BrickCandidate& candidate) const;
  /// Points, plane, OBB and outline geometry; the reason when it fails.
  /// `edges` (optional) replaces params_.edges in reading its edges: a
  /// tile's, read as its tiling read the seams (see seamReadingFor).
  std::optional<std::string> measure(const RgbdFrame& frame, const Segment& segment, const FrameContext& context,
                                     CloudProcessingTimings* cloud_timings, BrickCandidate& candidate,
                                     const EdgeEvidenceParams* edges = nullptr) const;
  /// Quad, corners, T1/T2, centre, dimensions and edge evidence (read with
  /// `edges`) from the mask and the plane.
  std::optional<std::string> fitOutline(const RgbdFrame& frame, const Segment& segment, const EdgeEvidenceParams& edges,
                                        BrickCandidate& candidate) const;
  /// Sets the candidate's corners (image and plane, edge 0 along its
  /// length) and what follows from them: size, centre, axis points.
  static void placeCorners(const PinholeCamera& camera, const QuadCorners& corners_px,
                           const std::array<Eigen::Vector3d, 4>& corners_m, BrickCandidate& candidate);
  /// Moves each edge with a wall beside it out to where the colour image
  /// shows the face ends (wallFootShiftPx).
  void moveEdgesToWallFeet(const RgbdFrame& frame, const EdgeEvidenceParams& edges,
                           const std::array<bool, 4>& beside_wall, BrickCandidate& candidate) const;
  /// The type of a measured face: the segment's colour's (HSV), or the
  /// catalogue size it matches (colour-free; when several fit, the one whose
  /// height the sides seen below the face's edges agree with).
  std::optional<std::string> assignType(const RgbdFrame& frame, const FrameContext& context, const Segment& segment,
                                        BrickCandidate& candidate) const;
  /// The type of a measured face by its size alone: the closest catalogue
  /// top, and the rivals (types sharing it, boxes lying on a side) the
  /// sides seen do not rule out as `type_doubt`; the reason when none fits.
  std::optional<std::string> typeBySize(const RgbdFrame& frame, const FrameContext& context,
                                        BrickCandidate& candidate) const;
  /// Colour-free, a face or tile cut off by the border or an occluder (a
  /// face after assignType refused it and no split was found): typed by
  /// the size of its visible part, with that doubt in `type_doubt`, so it
  /// is published partial. The reason when its shape or no catalogue top
  /// fits.
  std::optional<std::string> typeCutOffFace(const RgbdFrame& frame, const FrameContext& context,
                                            BrickCandidate& candidate) const;
  /// Colour-free, with a support given: why the type a face's size gave
  /// (`candidate.type_name`) cannot be its type, when nothing showing a top
  /// of the face's size (a type, a box lying on a side) could stand at the
  /// face's height above the support (levels around its foot included)
  /// while some catalogue box could: smaller boxes side by side make its
  /// top there (two box_small 0.15 m up are no box_large). Nullopt when
  /// one could, or nothing could (the face may stand on something the
  /// catalogue lacks: its height says nothing).
  std::optional<std::string> heightRulesOutType(const RgbdFrame& frame, const FrameContext& context,
                                                const BrickCandidate& candidate) const;
  /// Why a colour-free face's outline is no brick's top: too little of its
  /// quad filled, or too thick; nullopt when it may be one.
  std::optional<std::string> shapeMisfit(const BrickCandidate& candidate) const;
  /// Colour-free: turns the face's walls (edges to a wall something resting
  /// on it could be: BrickCandidate::resting_wall_m) back into its ends
  /// (kStepUp) when the face cannot go on beneath them, and nothing else
  /// cuts it off.
  void endAtWalls(const RgbdFrame& frame, const FrameContext& context, BrickCandidate& candidate) const;
  /// Whether some catalogue top larger than the face across its walls could
  /// be the face's, partly under something resting on it: one whose type
  /// could stand at the face's height above the given support (any, when
  /// no support is given).
  bool faceMayGoOnBeneathWalls(const RgbdFrame& frame, const FrameContext& context,
                               const BrickCandidate& candidate) const;
  /// A face's height above the given support (m), and the heights of the
  /// levels seen around its foot that it may also stand on.
  struct StandingHeight
  {
    double height_m;
    std::vector<double> levels_m;
  };
  /// The face's StandingHeight when it can tell types apart: a support is
  /// given, height_above_support_tolerance_m is on, and one of `shown` (the
  /// tops the face shows) could stand there; otherwise none.
  /// Whether a face's height above a given support can say what stands
  /// there: a support given, and height_above_support_tolerance_m on.
  bool heightTellsTypes(const FrameContext& context) const
  {
    return params_.height_above_support_tolerance_m > 0.0 && context.up.support_given;
  }
  std::optional<StandingHeight> standingHeight(const RgbdFrame& frame, const FrameContext& context,
                                               const BrickCandidate& candidate,
                                               const std::vector<const BrickType*>& shown) const;
  /// The extents a box whose top is `face`'s may have across an edge: the
  /// lengths and widths of the catalogue's poses (bottom, side, end)
  /// standing most exactly at its height (posesStandingMostExactly: the
  /// tops the tiler would lay there), or, without a height that tells,
  /// every catalogue extent.
  std::vector<double> extentsStandingThere(const RgbdFrame& frame, const FrameContext& context,
                                           const BrickCandidate& face) const;
  /// The side faces below the face's real edges (steps down, creases) seen
  /// down to their foot, measured up to `tallest_m`.
  std::vector<SideFaceEvidence> sidesSeenToTheirFoot(const RgbdFrame& frame, const FrameContext& context,
                                                     const BrickCandidate& candidate, double tallest_m) const;
  /// A plain box lying on a side or standing on an end (on a table) shows
  /// a face that no upright type's top (of `upright`) is within the
  /// dimension tolerance of, that one of its resting variants among
  /// `rivals` is, and that this variant fits by kTypeMarginM better than the
  /// best upright type (misfit `upright_misfit_m`, negative for none): that
  /// variant, else null. Nearer an upright top the face stays that type,
  /// the resting one in its doubt. (Letting a variant within only the
  /// classification tolerance win found 1-2 more boxes on a side in the
  /// table views and typed 2 stacked tops as lying.)
  const BrickType* restingInstead(const BrickCandidate& candidate, const std::optional<StandingHeight>& standing,
                                  const std::vector<SideFaceEvidence>& sides,
                                  const std::vector<const BrickType*>& upright,
                                  const std::vector<const BrickType*>& rivals, double upright_misfit_m) const;
  /// How far each of `types` could not stand at the face's height, its
  /// footing unseen counted (see closestType()); empty without a support.
  std::vector<double> standingMisfits(const std::vector<const BrickType*>& types,
                                      const std::optional<StandingHeight>& standing) const;
  /// Narrows a colour-free face's types (`fitting`) and their rivals to
  /// those that could stand at `height` (its standingHeight; see
  /// height_above_support_tolerance_m); unchanged without one, or when the
  /// height rules out all or none.
  void keepTypesStandingThere(const std::optional<StandingHeight>& height, std::vector<const BrickType*>& fitting,
                              std::vector<const BrickType*>& rivals) const;
  /// Colour-free: a complete face whose top smaller catalogue tops also
  /// make up (two box_small side by side are a box_large) is one brick only
  /// where the seam between them would show, as a line on a `plain` face,
  /// and does not (no trace of kFaintSeamStrength where they would meet).
  /// In a layer (`in_layer`: the face touches a neighbour on its plane), a
  /// printed face, or one with a trace, is made partial with the reason. A
  /// face standing alone is doubted only for a trace: its print is not
  /// read (a lone box is the likelier reading there). A plain face vouches
  /// for no seam only when bright enough for one to show
  /// (kMinGreyForSeamToShow); darker, it is partial.
  /// Without `plain`, the face's own pixels are read, and only for a top
  /// that smaller ones make up in a layer. A doubted face's type is in doubt
  /// too (`type_doubt`): one brick, or several smaller ones.
  /// Only smaller types standing at the face's height as exactly as any
  /// (typesStandingWhereTheFaceIs) make it up.
  void doubtComposedTop(const RgbdFrame& frame, const FrameContext& context, std::optional<bool> plain,
                        bool in_layer, BrickCandidate& candidate) const;
  /// Sets `complete` and `partial_reason` of a typed candidate (a reason
  /// from an edge names its `type_doubt` too, if any);
  /// `uniform_colour`: found by its plate colour, so a dark line along an
  /// edge is a seam (on printed boxes it may be print).
  void judgeCompleteness(const RgbdFrame& frame, const FrameContext& context, bool uniform_colour,
                         BrickCandidate& candidate) const;
  /// Places each of the face's `lines` (colour lines on a printed face) as
  /// its end where the catalogue's sizes do (judgeSizePlacedEdge; the face
  /// within size_placed_line_tolerance_m of `type`'s size), turning them
  /// into kSizePlacedLine; the first line not placed and why, if any.
  std::optional<std::pair<int, std::string>> placeLinesBySize(const RgbdFrame& frame, const FrameContext& context,
                                                              const BrickType& type, const std::vector<int>& lines,
                                                              BrickCandidate& candidate) const;
  /// What judgeCompleteness doubts of a face whose edges all end it: its
  /// plane going on outside the segment, a size not its type's, no up
  /// direction, or a type in doubt; nothing when none of these.
  std::optional<std::string> shapeDoubt(const RgbdFrame& frame, const FrameContext& context, const BrickType& type,
                                        const BrickCandidate& candidate) const;
  /// A measured face larger than one brick, cut into bricks: tiled (see
  /// tile()), or for a colour segment cut along its rows (see
  /// splitSideBySide()); empty when neither finds two bricks.
  std::optional<RoiOutcome> splitMerged(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                        const FrameContext& context, CloudProcessingTimings* cloud_timings) const;
  /// Colour-free, a measured face cut off by the border or an occluder that
  /// no split explained: published in `outcome` as partial, typed by what
  /// is seen of it (typeCutOffFace). False, and nothing published, when no
  /// type fits it (`reason` then says why, as typeCutOffFace does) or the
  /// face is not cut off, or has a colour.
  bool publishCutOff(const RgbdFrame& frame, const FrameContext& context, const Segment& segment,
                     BrickCandidate& candidate, RoiOutcome& outcome, std::string& reason) const;
  /// Colour-free: whether the face is large enough for two of the smallest type.
  bool mayHoldTwoBricks(const BrickCandidate& candidate) const;
  /// Whether a seam may cross `face`: always, unless it is one brick wide
  /// and the probe (probeSeamsAcross) sees none along it.
  bool mayShowASeamAcross(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& face) const;
  /// Whether no two tiles fit side by side across the face's width: any cut
  /// of a tiling then runs across the whole face (see seam_probe.h).
  bool oneTileWide(const BrickCandidate& candidate) const;
  /// Whether tiling `strip`, a face one brick wide and cut off, could keep
  /// a brick: some seam possible across it (probeSeamsAcross), and two of
  /// its seen ends and those seams a length of one of `types` apart.
  bool mayCutAWholeBrick(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& strip,
                         const std::vector<const BrickType*>& types) const;
  /// The colour-free tiler's types for a merged face, and whether its
  /// height fixes their size.
  struct TypesAtHeight
  {
    std::vector<const BrickType*> types;
    /// The types standing most exactly at the face's height (within
    /// kTypeMarginM of the least standingMisfitM) share one top.
    bool one_top_size = false;
  };
  /// A line placed as one tile's end (kSizePlacedLine) is where the tile
  /// across it begins: that tile's colour line there becomes one, and it is
  /// judged again (judgeCompleteness, doubtComposedTop), so that its own
  /// far line may be placed from it, round after round through a layer.
  /// Tiles with a `reason` are left out; `plain` ones see lines as seams.
  void placeLinesAcrossTiles(const RgbdFrame& frame, const FrameContext& context, const std::vector<char>& plain,
                             const std::vector<std::optional<std::string>>& reasons,
                             std::vector<BrickCandidate>& tiles) const;
  /// The poses of `shown` whose top could be at `face`'s height above the
  /// given support (typesStandingAt, levels around its foot read only where
  /// a pose standing on one could still be exact), within kTypeMarginM of
  /// the least standingMisfitM; nothing when no support is given or none
  /// could stand there.
  std::optional<std::vector<const BrickType*>> posesStandingMostExactly(
      const RgbdFrame& frame, const FrameContext& context, const BrickCandidate& face,
      const std::vector<const BrickType*>& shown) const;
  /// Those of `types` whose top could be at `face`'s height above the
  /// given support, on their bottom, a side or an end (typesStandingAt,
  /// levels around its foot included), most exactly: within kTypeMarginM
  /// of the least standingMisfitM. `types` (one_top_size false) when no
  /// support is given or none could stand there.
  TypesAtHeight typesStandingWhereTheFaceIs(const RgbdFrame& frame, const FrameContext& context,
                                            const BrickCandidate& face,
                                            const std::vector<const BrickType*>& types) const;
  /// Whether most of the surface around the segment's outline lies below
  /// its plane (see raised_layer.h).
  bool standsUpFromItsSurroundings(const RgbdFrame& frame, const Segment& segment, const PlaneFit& plane) const;
  /// The edge evidence and tiling settings a merged face's seams are read
  /// with (see seamReadingFor).
  struct SeamReading
  {
    EdgeEvidenceParams edges;
    FaceTilingParams tiling;
  };

  /// The candidates and rejections of tiling a measured segment; empty
  /// when no tiling of two or more bricks was found (or, with
  /// `seams_required`, when any cut lacks a seen seam).
  /// `tried` (optional) receives the tiling found, used or not;
  /// `only_types` (optional) replaces the segment's types.
  std::optional<RoiOutcome> tile(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                                 const FrameContext& context, bool seams_required,
                                 CloudProcessingTimings* cloud_timings, FaceTiling* tried = nullptr,
                                 const std::vector<const BrickType*>* only_types = nullptr) const;

  /// A face of one plate colour tiled greedily and with every brick laid
  /// each way; the greedy tiling unless a one-way one sees more seams.
  FaceTiling tileEachWay(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                         const std::vector<const BrickType*>& types, const SeamReading& seams) const;
  /// Colour-free tiling of a face larger than any brick: each type alone
  /// (the smallest first), then all together; the finest tiling whose every
  /// cut is seen (a groove or a line), or none. With `sizes_place_cuts`
  /// (the face's height leaves one top size: TypesAtHeight), a tiling with
  /// no cut seen is kept too.
  FaceTiling tileBySeenSeams(const RgbdFrame& frame, const Segment& segment, const BrickCandidate& measured,
                             const std::vector<const BrickType*>& types, const SeamReading& seams,
                             bool sizes_place_cuts) const;
  /// How the tiler reads a face's seams, given its uniformity and its level
  /// `face_grey` in the grey its lines are read in (faceGreyLevel): on a
  /// plain face a line is a seam, read against its light
  /// (plain_seam_line_share) and confirmed along the lines cuts share
  /// (FaceTilingParams::confirm_along_lines); elsewhere params_ as they are.
  SeamReading seamReadingFor(const ColourUniformity& face_uniformity, double face_grey) const;

  BrickCatalogue catalogue_;
  /// The catalogue's boxes lying on a side or standing on an end, as rivals
  /// of a colour-free face's type (see type_evidence.h).
  std::vector<BrickType> lying_variants_;
  /// The heights stacks of catalogue items make: what a colour-free face's
  /// height above the supporting plane allows of its type.
  StackHeights stack_heights_;
  /// Every extent a catalogue top may have across an edge, in any pose: the
  /// ends a box may have where only a colour line marks one (size_placed_edge.h).
  std::vector<double> catalogue_extents_m_;
  RoiFilterParams params_;
  CloudProcessor cloud_processor_;
};
}  // namespace brick_pose
