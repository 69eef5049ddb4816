// RoiFilter, part 3 of 3: telling a face's catalogue type (by colour, or by
// size, height above the support and the sides seen) and doubting it where
// the evidence allows another. roi_filter.cpp measures faces and judges them
// complete; roi_filter_tiling.cpp splits merged ones.

#include "brick_pose/roi/roi_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "brick_pose/catalogue/resting.h"
#include "brick_pose/common/rounding.h"
#include "brick_pose/roi/colour_uniformity.h"
#include "brick_pose/roi/foot_levels.h"
#include "brick_pose/roi/type_evidence.h"

#include "roi_filter_internal.h"

namespace brick_pose
{
using roi_internal::addTypeDoubt;
using roi_internal::typesFor;
using roi_internal::describe;
using roi_internal::sideAxis;
using roi_internal::anyTruncated;
using roi_internal::truncation;
using roi_internal::kFaintSeamStrength;

namespace
{
/// A wall the camera sees standing at a face's edge, as high as an item
/// resting on the face could be, ends the face unless a catalogue top
/// larger than the face by more than this (m) across the wall could be the
/// face's (see faceMayGoOnBeneathWalls): a strip this narrow under a
/// resting item is within the error of the face's measured size.
constexpr double kMaxCoveredByRestingWallM = 0.005;

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

/// A plain face vouches that no seam crosses it only this bright (mean grey
/// level): the closed seam of two of the rig's red bricks in low light (mean
/// grey 28) is 2 levels deep, under any trace; in normal light (90) seams are
/// 24-47 levels.
constexpr double kMinGreyForSeamToShow = 50.0;

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
/// The face's thickness beyond its plane's noise (m). The box is measured
/// on plane inliers, whose spread grows with depth noise; only thickness
/// beyond that spread says "not a flat face".
double thicknessBeyondNoiseM(const BrickCandidate& candidate)
{
  const double noise_spread_m = 6.0 * candidate.plane.rms_m;
  return candidate.obb.valid ? std::max(0.0, candidate.obb.extents_m.z() - noise_spread_m) : 0.0;
}
}  // namespace

std::optional<std::string> RoiFilter::assignType(const RgbdFrame& frame, const FrameContext& context,
                                                const Segment& segment, BrickCandidate& candidate) const
{
  if (!segment.type_name.empty())
  {
    const BrickType* type = catalogue_.find(segment.type_name);
    if (!type) return "unknown brick type '" + segment.type_name + "'";
    if (auto reason = checkTopFaceDimensions(candidate.length_m, candidate.width_m, thicknessBeyondNoiseM(candidate),
                                             *type, params_.dimensions))
      return segment.type_name + ": " + *reason;
    candidate.type_name = type->name;
    candidate.typed_by_colour = true;
    return std::nullopt;
  }

  // Colour-free: only whole faces can be told apart by size (half a blue
  // brick looks like a green one); a face cut off is split if it can be,
  // and else typed as a doubt (typeCutOffFace).
  endAtWalls(frame, context, candidate);
  if (anyTruncated(candidate)) return "face is cut by an occluder or the image border (" + truncation(candidate) + ")";
  if (std::optional<std::string> misfit = shapeMisfit(candidate)) return misfit;
  return typeBySize(frame, context, candidate);
}

std::optional<std::string> RoiFilter::shapeMisfit(const BrickCandidate& candidate) const
{
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
  const double thickness_m = thicknessBeyondNoiseM(candidate);
  if (thickness_m > params_.dimensions.max_thickness_m)
    return describe("thickness", thickness_m, "m exceeds", params_.dimensions.max_thickness_m);
  return std::nullopt;
}

std::optional<std::string> RoiFilter::typeCutOffFace(const RgbdFrame& frame, const FrameContext& context,
                                                     BrickCandidate& candidate) const
{
  // What is seen of a brick cut off may be a whole smaller one's top, or a
  // larger one's part: the visible part's type is published as a doubt, so
  // the face stays partial (its cut edges alone make it so) and says why.
  const std::string cut = "face is cut by an occluder or the image border (" + truncation(candidate) + ")";
  // Its visible part must be a catalogue top as closely as a whole face's
  // size must be (judgeCompleteness): a fragment only roughly the size of
  // a small type is no reading of one. Checked first: most faces cut off
  // fit none, and typing by size reads their sides.
  const double tolerance_m = params_.dimensions.tolerance_m;
  auto fitsClosely = [&](const BrickType& type) {
    return showsTop(type, candidate.length_m, candidate.width_m, tolerance_m);
  };
  if (std::none_of(catalogue_.types().begin(), catalogue_.types().end(), fitsClosely))
  {
    std::ostringstream text;
    text.precision(3);
    text << cut << "; its visible part (" << candidate.length_m << " x " << candidate.width_m
         << " m) fits no catalogue top within the dimension tolerance";
    return text.str();
  }
  if (std::optional<std::string> misfit = shapeMisfit(candidate)) return cut + "; " + *misfit;
  if (std::optional<std::string> no_type = typeBySize(frame, context, candidate)) return cut + "; " + *no_type;
  const std::optional<BrickType> type = catalogue_.findResting(candidate.type_name);
  if (type && !fitsClosely(*type))
    return cut + "; its visible part is no " + type->name + " top within the dimension tolerance";
  const std::string doubt = "it is cut off, and its type is the one its visible part fits (a larger one's part may look so)";
  addTypeDoubt(candidate, doubt);
  return std::nullopt;
}

std::optional<std::string> RoiFilter::heightRulesOutType(const RgbdFrame& frame, const FrameContext& context,
                                                         const BrickCandidate& candidate) const
{
  const std::optional<BrickType> own = catalogue_.findResting(candidate.type_name);
  const double tolerance_m = params_.height_above_support_tolerance_m;
  if (!own || !heightTellsTypes(context)) return std::nullopt;
  const double height_m = context.up.heightAboveSupport(candidate.centroid_m);
  // Most faces stand where their type does: that needs no levels read.
  if (!typesStandingAt({&*own}, height_m, {}, stack_heights_, tolerance_m).empty()) return std::nullopt;
  // What shows a top of the face's size (a type, or a box lying on a side),
  // and what stands anywhere at all.
  std::vector<const BrickType*> shown, all;
  for (const BrickType& type : catalogue_.types())
  {
    all.push_back(&type);
    if (showsTop(type, candidate.length_m, candidate.width_m, params_.classification_tolerance_m)) shown.push_back(&type);
  }
  for (const BrickType& variant : lying_variants_)
  {
    all.push_back(&variant);
    if (showsTop(variant, candidate.length_m, candidate.width_m, params_.classification_tolerance_m))
      shown.push_back(&variant);
  }
  // Nothing stands there (a plinth?), or something showing its top does:
  // checked without the levels first, which only add places to stand.
  if (typesStandingAt(all, height_m, {}, stack_heights_, tolerance_m).empty() ||
      !typesStandingAt(shown, height_m, {}, stack_heights_, tolerance_m).empty())
    return std::nullopt;
  const std::vector<double> levels_m =
      levelsAroundFoot(frame, candidate.mask, candidate.bounding_box_px, candidate.plane, context.up, tolerance_m);
  if (!typesStandingAt(shown, height_m, levels_m, stack_heights_, tolerance_m).empty()) return std::nullopt;
  std::ostringstream text;
  text.precision(3);
  text << "its top is " << height_m << " m above the support, where no " << own->name << " ("
       << own->height_m << " m tall) stands: smaller boxes side by side may make it up";
  return text.str();
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
  double best_misfit_m = 0.0;
  const BrickType* best = closestType(fitting, candidate.length_m, candidate.width_m, sides,
                                      standingMisfits(fitting, standing), &best_misfit_m);
  if (const BrickType* lying = restingInstead(candidate, standing, sides, fitting, rivals, best ? best_misfit_m : -1.0))
    best = lying;
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
  const std::vector<const BrickType*> open =
      rivalsInDoubt(rivals, *best, candidate.length_m, candidate.width_m, sides, params_.sides, on_support_alone);
  candidate.type_doubt = typeDoubtText(*best, open);
  candidate.other_possible_types.clear();
  for (const BrickType* type : open) candidate.other_possible_types.push_back(type->name);
  return std::nullopt;
}

const BrickType* RoiFilter::restingInstead(const BrickCandidate& candidate,
                                           const std::optional<StandingHeight>& standing,
                                           const std::vector<SideFaceEvidence>& sides,
                                           const std::vector<const BrickType*>& upright,
                                           const std::vector<const BrickType*>& rivals,
                                           double upright_misfit_m) const
{
  // A type holds the face where its top is within the dimension tolerance
  // of the face's size: an upright one keeps it, a resting one must.
  const auto holds = [&](const BrickType* type) {
    return showsTop(*type, candidate.length_m, candidate.width_m, params_.dimensions.tolerance_m);
  };
  if (std::any_of(upright.begin(), upright.end(), holds)) return nullptr;
  std::vector<const BrickType*> resting;
  for (const BrickType* rival : rivals)
    if (rival->resting != Resting::kUpright && mayRestOtherwise(*rival) && holds(rival)) resting.push_back(rival);
  double misfit_m = 0.0;
  const BrickType* lying =
      closestType(resting, candidate.length_m, candidate.width_m, sides, standingMisfits(resting, standing), &misfit_m);
  if (!lying || (upright_misfit_m >= 0.0 && misfit_m + kTypeMarginM > upright_misfit_m)) return nullptr;
  return lying;
}

std::vector<double> RoiFilter::standingMisfits(const std::vector<const BrickType*>& types,
                                               const std::optional<StandingHeight>& standing) const
{
  if (!standing) return {};
  std::vector<double> misfits_m = standingMisfitsM(types, standing->height_m, stack_heights_);
  // Of types tied there, the one whose footing shows beside the face.
  for (std::size_t i = 0; i < misfits_m.size(); ++i)
    misfits_m[i] += footingUnseenPenaltyM(*types[i], standing->height_m, standing->levels_m,
                                          params_.height_above_support_tolerance_m);
  return misfits_m;
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
  if (!heightTellsTypes(context)) return std::nullopt;
  const double tolerance_m = params_.height_above_support_tolerance_m;
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

std::vector<double> RoiFilter::extentsStandingThere(const RgbdFrame& frame, const FrameContext& context,
                                                   const BrickCandidate& face) const
{
  if (!heightTellsTypes(context)) return catalogue_extents_m_;
  std::vector<const BrickType*> shown = typesFor(catalogue_, "");
  for (const BrickType& pose : lying_variants_) shown.push_back(&pose);
  const std::optional<std::vector<const BrickType*>> poses = posesStandingMostExactly(frame, context, face, shown);
  if (!poses) return catalogue_extents_m_;
  std::vector<double> extents_m;
  for (const BrickType* pose : *poses)
  {
    extents_m.push_back(pose->length_m);
    extents_m.push_back(pose->width_m);
  }
  return extents_m;
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

void RoiFilter::doubtComposedTop(const RgbdFrame& frame, const FrameContext& context, std::optional<bool> plain,
                                 bool in_layer, BrickCandidate& candidate) const
{
  if (!candidate.complete) return;
  const std::optional<BrickType> type = catalogue_.findResting(candidate.type_name);
  if (!type) return;
  if (!smallerTypeTiling(catalogue_.types(), *type, params_.dimensions.tolerance_m).type) return;
  // Smaller boxes side by side stand where the face is, as exactly as any
  // type could (the types the tiler lays there): two box_small 0.25 m up
  // would need a box beneath them no catalogue has, and two box_flat there
  // a box lying beneath each, 2 cm off, where a box_large stands on the
  // ground.
  const std::vector<const BrickType*> exact =
      typesStandingWhereTheFaceIs(frame, context, candidate, typesFor(catalogue_, "")).types;
  std::vector<BrickType> standing;
  for (const BrickType* each : exact) standing.push_back(*each);
  const Composition composition = smallerTypeTiling(standing, *type, params_.dimensions.tolerance_m);
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
}  // namespace brick_pose
