#pragma once
// What the frame shows beyond one edge of a face. A face is a brick's whole
// top only when every edge is where the brick ends: the surface beyond it
// lies lower (a step down, or the brick's own side face bending away), or a
// neighbour touches it along a seam (a groove in depth or a dark line in
// colour). An edge along the image border, along a nearer surface (an
// occluder) or across a plane that simply continues (the end of a colour
// mask, a cut made from catalogue sizes alone) says nothing about where the
// brick ends.
//
// Each edge is probed in a few stretches; each stretch aggregates a depth
// and intensity profile across the edge over all its samples (medians), so
// a seam a millimetre or two deep under several millimetres of per-pixel
// noise still shows. An edge is only as good as its worst stretch.

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/Core>

#include "brick_pose/frame/rgbd_frame.h"
#include "brick_pose/geometry/plane_fit.h"

namespace brick_pose
{
enum class EdgeKind : std::uint8_t
{
  kUnknown = 0,  ///< Not examined.
  kStepDown,     ///< Beyond the edge the surface drops away from the face (ground, a lower brick, a gap).
  kCrease,       ///< The surface bends away at the edge without a jump (the brick's side face seen obliquely).
  kSeam,         ///< The plane continues, but a groove in depth runs along the edge (touching faces).
  kColourLine,   ///< The plane continues with a line (darker or brighter) along the edge but no
                 ///< groove: a seam between touching plates of one colour, or just print on a box.
  kOcclusion,    ///< A nearer surface lies beyond the edge: the face may continue under it.
  kStepUp,       ///< A nearer surface all along the edge, at one height, that as a wall standing
                 ///< there would hide at most max_hidden_by_wall_m of the face: a taller neighbour
                 ///< beside the face (the face ends) or something resting on it (the face goes on
                 ///< beneath). Only the wall's height tells which: RoiFilter turns it into
                 ///< kOcclusion when a catalogue item resting on the face could be that high.
  kImageBorder,  ///< The edge runs along the image border: the face may continue outside the image.
  kMaskEdge,     ///< The plane continues beyond the edge with nothing marking it (a mask or split boundary).
  kNoDepth,      ///< Too little depth beyond the edge to tell.
  kOverrun,      ///< Inside the edge the pixels are off the face's plane: the mask runs over the
                 ///< face's edge (onto a side face of the same colour), so the edge is not the face's.
  kDropBesideWall,  ///< Along part of the edge the surface drops away, along the rest it rises to
                    ///< walls standing on the edge that the camera sees (hiding none of the face):
                    ///< the drop shows the face ends at this line, so the walls stand beside it
                    ///< (neighbours), not on it. A low box beside the end of a taller row.
  kSizePlacedLine,  ///< A colour line on a printed face that the catalogue's sizes place as the box's
                    ///< end (see size_placed_edge.h); set by RoiFilter, never by classifyEdge().
};

/// True for the kinds that show where a brick ends: a step down, a crease,
/// a seam, a step up to a wall (once RoiFilter has ruled out, by its
/// height, that it rests on the face), a line the catalogue's sizes place,
/// and a colour line only on a face of uniform colour (a plate found by its
/// colour), not on printed boxes where lines are everywhere.
bool isRealEdge(EdgeKind kind, bool uniform_colour = false);
/// Short name: "step down", "crease", "seam", "occlusion boundary", ...
std::string toString(EdgeKind kind);

/// The four edges of a face (edge k runs from corner k to corner k + 1).
using EdgeKinds = std::array<EdgeKind, 4>;

struct EdgeEvidenceParams
{
  /// Profiles reach this far (pixels) to either side of the edge.
  int probe_px = 8;
  /// Profile samples closer than this to the edge are left out of the
  /// inside/outside bands (the edge pixels are mixtures, and D4xx depth
  /// fattens a foreground a few pixels beyond its edge).
  int inner_gap_px = 2;
  /// The edge is examined in this many stretches, each judged on its own.
  int stretches = 4;
  /// Samples along a stretch are about this far apart (pixels).
  double sample_spacing_px = 1.5;
  /// Ends of the edge left out (fraction of its length): corners are
  /// rounded and mixed.
  double end_margin_fraction = 0.08;
  /// Beyond the edge, a surface more than max(min_step_m, step_noise_factor
  /// * plane rms) from the face's plane is a different surface; so is one
  /// whose rows lie, by their median over a stretch, half that below both
  /// the plane and the inside band (far noisy faces, whose rows alone
  /// rarely clear the step).
  double min_step_m = 0.008;
  double step_noise_factor = 4.0;
  /// That step (m) for a face whose plane fits its points to `plane_rms_m`.
  double stepM(double plane_rms_m) const { return std::max(min_step_m, step_noise_factor * plane_rms_m); }
  /// A stretch is cut by the border when at least this fraction of its
  /// samples has the outside band (partly) outside the image.
  double max_border_fraction = 0.3;
  /// Fewer samples with depth beyond the edge than this fraction: no depth.
  double min_depth_fraction = 0.3;
  /// Seam tests on a coplanar continuation: a groove (the middle of the
  /// profile farther than both sides) at least this deep, or a dark line at
  /// least this many grey levels darker than both sides (grey read in the
  /// face's own colour, FaceGrey); each also at least
  /// seam_noise_factor standard errors of the along-edge scatter. (Lines
  /// count either way: darker or brighter than both sides.)
  double min_groove_m = 0.0008;
  double min_line_contrast = 6.0;
  double seam_noise_factor = 3.0;
  /// The seam may lie this many pixels off the fitted edge.
  int seam_search_px = 3;
  /// Inside the edge, the face's pixels lying between min_step_m and this
  /// far below its plane are a side face the mask ran onto (kOverrun);
  /// farther below is a hole in a joined face (the ground seen between two
  /// pieces of one plate under a cover), judged by what lies beyond.
  double max_overrun_m = 0.06;
  /// A nearer surface all along an edge is a wall standing there
  /// (kStepUp) when, standing upright on the edge, it would hide at most
  /// this much (m) of the face across the edge: none when the camera sees
  /// the wall, a strip h x tan(view angle) when it looks over it. Any strip
  /// hidden is the face not seen whole (with 0.01 m, flat boxes 2 % hidden
  /// beside tall ones were published complete).
  double max_hidden_by_wall_m = 0.0;
  /// Beside a wall the camera sees, the stereo matcher carries the wall's
  /// depth up to this many pixels over the face (its fattening plus half
  /// its matching window: 3 + 3 for a D4xx), so the face's depth ends short
  /// of its edge; the edge is sought in the colour image that far out
  /// (wallFootShiftPx). 0 leaves the depth edge as it is.
  int max_wall_foot_shift_px = 8;
  /// At a step down the stereo matcher carries the face's depth this many
  /// pixels at most over the lower surface beyond (a D4xx fattens a
  /// foreground by about 3), so the depth edge lies outside the face's
  /// edge and the face measures long; the edge is sought in the colour
  /// image that far in (stepEdgeInsetPx), to share a complete face's excess
  /// between its ends (RoiFilterParams::place_on_catalogue_size). 0: not
  /// sought.
  int max_step_inset_px = 6;

  void validate() const;  ///< Throws ConfigError naming the field.
};

/// What one stretch or edge showed, with the numbers behind it.
struct EdgeEvidence
{
  EdgeKind kind = EdgeKind::kUnknown;
  /// Median signed distance (m) of the surface beyond the edge from the
  /// face's plane: positive = nearer the camera (above the face), negative
  /// = below it.
  double outside_offset_m = 0.0;
  double groove_m = 0.0;       ///< Depth of a groove along the edge (m, > 0 farther).
  double line_contrast = 0.0;  ///< Grey levels the edge line is darker (or brighter) than both sides.
  /// Share of the depth samples just inside the edge that lie above the
  /// face's plane (something reaching over the face there).
  double inside_above_fraction = 0.0;
  /// Lowest and highest wall (m above the plane) seen along a kStepUp or
  /// kDropBesideWall edge, or a kOcclusion that is walls the camera sees
  /// all along it at several heights (two taller neighbours, or boxes
  /// resting on the face); NaN otherwise.
  double lowest_wall_m = std::numeric_limits<double>::quiet_NaN();
  double highest_wall_m = std::numeric_limits<double>::quiet_NaN();
  /// A kOcclusion stretch whose rows only rise to a wall the camera sees
  /// (hiding none of the face) or stay on the face's plane, with none
  /// dropping away and the face clear inside it: a neighbour's wall ending
  /// beside one of the face's own height, as at a corner of a layer.
  bool wall_beside_level = false;
};

/// Classifies the edge from `a_px` to `b_px` of a face lying on `plane`;
/// `outward_px` is the image direction away from the face (need not be
/// unit). The worst stretch decides: border, then occlusion, then no depth,
/// then a mask edge; among real kinds a seam, then a crease, then a step.
/// A step up stands only when every stretch is one, at one height
/// (within min_step_m); stretches that only step up to walls the camera
/// sees or drop away, with a drop among them, are kDropBesideWall; any
/// other mix with a wall is an occlusion.
EdgeEvidence classifyEdge(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                          const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                          const EdgeEvidenceParams& params = EdgeEvidenceParams());

/// Whether at least `min_share` of the stretches of the line from `a_px` to
/// `b_px` across a face (both sides on `plane`) show a mark: anything but
/// the plane going on with nothing on it (kMaskEdge), so a line, groove or
/// step, or a border, occluder or missing depth that may hide one. A box
/// ends only along a line marked all along it; print marks stretches.
/// True for a line too short to judge.
bool markedAlong(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                 const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px, double min_share,
                 const EdgeEvidenceParams& params = EdgeEvidenceParams());

/// The ends of the same edge, which classifyEdge() leaves out (the
/// end_margin_fraction next to each corner), judged the same way: kOcclusion
/// when a nearer surface reaches over either end, else kUnknown. Something
/// lying across a face's corner hides it from the edges' own profiles. A
/// step up at an end is such a surface too, unless the edge is itself kept
/// as the face's end beside walls from `lowest_wall_m` to `highest_wall_m`
/// high (NaN: none; one height: pass it once), and the end's wall lies in
/// that range (within min_step_m): then it is one of those walls. Beside
/// such an edge, a wall of another height the camera sees at an end, with
/// the face clear just inside it, is a neighbour beside the corner: kUnknown.
/// So is, beside any edge, an end that only rises to a wall the camera sees
/// or stays level (EdgeEvidence::wall_beside_level).
EdgeKind occlusionAtEdgeEnds(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                             const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                             const EdgeEvidenceParams& params = EdgeEvidenceParams(),
                             double lowest_wall_m = std::numeric_limits<double>::quiet_NaN(),
                             double highest_wall_m = std::numeric_limits<double>::quiet_NaN());

/// How far (pixels, along `outward_px`) the face's true edge lies beyond
/// its depth edge `a_px`-`b_px` where a wall stands there (kStepUp,
/// kDropBesideWall): where the first feature out to max_wall_foot_shift_px
/// that takes the face's grey level (the median along the edge) off its
/// level inside the edge by more than the line contrast (the wall's foot, a
/// rim or a seam) reaches half its peak. 0 when the colour already changes
/// at the depth edge; NaN when it does not change within reach or the edge
/// cannot be read.
double wallFootShiftPx(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                       const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                       const EdgeEvidenceParams& params = EdgeEvidenceParams());

/// How far (pixels, against `outward_px`) the face's true edge lies inside
/// its depth edge `a_px`-`b_px` at a step down: where the grey level (the
/// median along the edge) passes half-way from the face's level, read
/// clear of max_step_inset_px inside, to the level of what lies beyond the
/// depth edge. 0 when the colour changes at the depth edge or beyond; NaN
/// when the two levels differ by less than the line contrast (a lower top
/// of the same cardboard), the change is not within reach, or the edge
/// cannot be read.
double stepEdgeInsetPx(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                       const Eigen::Vector2d& b_px, const Eigen::Vector2d& outward_px,
                       const EdgeEvidenceParams& params = EdgeEvidenceParams());

/// Evidence of a seam along a line that crosses a face (both sides on
/// `plane`): the groove depth and dark-line contrast over the whole line,
/// and whether they clear the thresholds of `params`. Used to place and
/// check the cuts between touching faces.
struct SeamScore
{
  double groove_m = 0.0;
  double line_contrast = 0.0;
  /// Best of the two, in standard errors of its along-line scatter.
  double strength = 0.0;
  int samples = 0;
  bool groove_seen = false;  ///< The groove clears min_groove_m and seam_noise_factor standard errors.
  bool line_seen = false;    ///< The line clears min_line_contrast and seam_noise_factor standard errors.
  bool seen = false;         ///< Either.
};
SeamScore scoreSeam(const RgbdFrame& frame, const PlaneFit& plane, const Eigen::Vector2d& a_px,
                    const Eigen::Vector2d& b_px, const EdgeEvidenceParams& params = EdgeEvidenceParams());
}  // namespace brick_pose
