#pragma once
// What tells catalogue types apart when a face is typed by its size alone
// (colour-free): the face's length and width, and the heights of the side
// faces seen below its edges. Several types can share a top (a flat and a
// tall box), and a box lying on a side or standing on an end shows a face
// near another type's top; the closest type is then a guess, and a guess is
// never published as a complete top.

#include <cstdint>
#include <string>
#include <vector>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/roi/side_faces.h"

namespace brick_pose
{
/// How much worse a rival type must fit (m of error, over the face's length
/// and width and the heights of the sides reaching the support together)
/// before the evidence rules it out. On the real mOSD scenes Kinect measures
/// sides within 6 mm of the catalogue height and tops within about 12 mm.
constexpr double kTypeMarginM = 0.015;

/// What a side seen ending on something other than the support, shorter
/// than a type by kTypeMarginM or more, adds to that type's misfit (m): the
/// type needs the rest of its side hidden by a neighbour exactly as high as
/// the side's foot. Less than kStackItemPenaltyM: it only breaks ties.
constexpr double kHiddenSidePenaltyM = 0.005;

/// Whether `type`'s top (or a lying variant's face up) is a face of
/// `length_m` x `width_m`, each within `tolerance_m`.
bool showsTop(const BrickType& type, double length_m, double width_m, double tolerance_m);

/// The type in `fitting` closest to a face of `length_m` x `width_m` and,
/// where sides are seen to their foot, to their height. A side reaching the
/// supporting plane measures the height. A side ending on anything else is
/// only a lower bound: the level at its foot may be a box the face stands
/// on, or a lower neighbour beside it, hiding the rest of the side (a box
/// 0.15 m tall beside one 0.07 m tall shows 0.08 m); a type shorter than it
/// fits worse by the difference, a taller one no worse. Where given,
/// `standing_misfits_m[i]` (see standingMisfitM) adds how far `fitting[i]`
/// could not stand at the face's height: among types otherwise tied, the
/// one standing most exactly where the face is wins. Null for no types;
/// `misfit_m`, when given, receives the winner's misfit (m).
const BrickType* closestType(const std::vector<const BrickType*>& fitting, double length_m, double width_m,
                             const std::vector<SideFaceEvidence>& sides,
                             const std::vector<double>& standing_misfits_m = {}, double* misfit_m = nullptr);

/// The faces of `types` other than their tops that differ from the top by
/// kTypeMarginM or more, each as a type whose "top" is that face, as tall as
/// the dimension left over, named "<type> lying on a side" or "<type>
/// standing on an end". A brick whose side is its top's size adds nothing:
/// that face looks the same.
std::vector<BrickType> lyingVariants(const std::vector<BrickType>& types);

/// Why `best` is not certain: the rivals (other types, lying variants) that
/// the evidence does not rule out, as "type uncertain: ..."; empty when it
/// rules all out. A rival is ruled out when it fits the face's size and the
/// sides reaching the support kTypeMarginM worse in all. A side ending above
/// the support and taller than a rival may be the rival's side and, flush
/// below it, the side of what it stands on (a flat box on another shows one
/// side twice its height): such a side rules out only the rivals of
/// `on_support_alone`, beneath which nothing can be (see
/// standsOnSupportAlone). Rivals within kTypeMarginM of `best` in every
/// dimension are the same shape: no doubt.
std::string typeDoubt(const std::vector<const BrickType*>& rivals, const BrickType& best, double length_m,
                      double width_m, const std::vector<SideFaceEvidence>& sides,
                      const SideFaceParams& params = SideFaceParams(),
                      const std::vector<const BrickType*>& on_support_alone = {});

/// The rivals typeDoubt names, in `rivals`' order: the types (and lying
/// variants) the face may be as well as `best`.
std::vector<const BrickType*> rivalsInDoubt(const std::vector<const BrickType*>& rivals, const BrickType& best,
                                            double length_m, double width_m,
                                            const std::vector<SideFaceEvidence>& sides,
                                            const SideFaceParams& params = SideFaceParams(),
                                            const std::vector<const BrickType*>& on_support_alone = {});

/// typeDoubt's text for `best` and the rivals left open; empty when none is.
std::string typeDoubtText(const BrickType& best, const std::vector<const BrickType*>& open);

/// The heights a stack of catalogue items can make: any number of them, in
/// any of the orientations they can lie in, one on another. A top `h` above
/// the supporting plane of a box `b` tall means the box stands on the
/// support (h = b) or on items whose heights add up to h - b; where no
/// stack can make that, the box is not of that type, whatever its top's
/// size. (The pile is assumed to hold catalogue items, and to stand on the
/// plane taken as the support.)
class StackHeights
{
public:
  /// From the heights of the items (m, > 0); stacks up to `max_height_m`
  /// are known, on a grid of `resolution_m`.
  explicit StackHeights(const std::vector<double>& item_heights_m, double max_height_m = 3.0,
                        double resolution_m = 0.001);
  /// Of the items of `types`, each on its bottom, a side or an end.
  static StackHeights of(const std::vector<BrickType>& types);

  /// Whether some stack (none at all included) is within `tolerance_m` of
  /// `height_m`; above max_height_m every height is taken as makeable.
  bool canMake(double height_m, double tolerance_m) const;
  /// How far `height_m` is from a stack (m, to the grid's resolution),
  /// each item of it adding `per_item_m` (>= 0): the least such sum; 0
  /// above max_height_m, infinite for a height that is not finite.
  double misfitM(double height_m, double per_item_m = 0.0) const;

private:
  static constexpr std::uint8_t kUnmakeable = 255;
  double resolution_m_;
  std::vector<std::uint8_t> items_;  ///< fewest items making each height / resolution_m_, or kUnmakeable
};

/// What each item beneath a face adds to the misfit of the type standing
/// on them (m): of two ways to stand at a height, nearly as exact, the one
/// of fewer items is the likelier. Without it, any height above a few
/// items is some stack's to the millimetre (a box_small's top 0.55 m up is
/// also a box_flat's on five items), and the guess between types sharing a
/// top would follow noise.
constexpr double kStackItemPenaltyM = 0.01;

/// How far `type`'s top would at best be from `height_above_support_m` (m)
/// standing on the support or on a stack of items on it, with
/// kStackItemPenaltyM for each item (0: standing exactly on the support).
/// Levels seen around a face's foot are left out here: a level only widens
/// the doubt (typesStandingAt) and only breaks ties (footingUnseenPenaltyM).
double standingMisfitM(const BrickType& type, double height_above_support_m, const StackHeights& stacks);
/// standingMisfitM of each of `types`, in their order.
std::vector<double> standingMisfitsM(const std::vector<const BrickType*>& types, double height_above_support_m,
                                     const StackHeights& stacks);

/// What a type loses (m, added to its standing misfit) when the surface it
/// would stand on is not seen beside the face: of two types whose tops are
/// one size and whose heights stack to the face's either way (a box_flat on
/// a box_small, or the reverse), the one whose footing shows around the
/// face's foot, as a lower box's top at the face's height less the type's,
/// is the likelier. A neighbour just that high could show the same, so the
/// other type stays in doubt (rivalsInDoubt); this only names the likelier.
/// Smaller than any misfit that tells types apart (kStackItemPenaltyM,
/// kHiddenSidePenaltyM).
constexpr double kFootingUnseenPenaltyM = 0.003;

/// kFootingUnseenPenaltyM when `type`, its top `height_above_support_m`
/// up, would stand neither on the support (its bottom within `tolerance_m`
/// of it) nor on one of `levels_m` (levelsAroundFoot) within `tolerance_m`;
/// else 0.
double footingUnseenPenaltyM(const BrickType& type, double height_above_support_m,
                             const std::vector<double>& levels_m, double tolerance_m);

/// Whether `type`, its top `height_above_support_m` up, can only be
/// standing on the support itself: its bottom within `tolerance_m` of the
/// support, too low for any item beneath (every catalogue item is taller
/// than twice the tolerance) and below every one of `levels_m`. Also true
/// of a type taller than the face's height, which could not stand there at
/// all (typesStandingAt leaves it out).
bool standsOnSupportAlone(const BrickType& type, double height_above_support_m, const std::vector<double>& levels_m,
                          double tolerance_m);
/// The types of `rivals` that standsOnSupportAlone, in their order.
std::vector<const BrickType*> typesOnSupportAlone(const std::vector<const BrickType*>& rivals,
                                                  double height_above_support_m, const std::vector<double>& levels_m,
                                                  double tolerance_m);

/// The types of `rivals` (catalogue types and lying variants) that could
/// show their top `height_above_support_m` above the supporting plane:
/// standing on it, on one of `levels_m` (heights above it of other surfaces
/// the face may stand on), or on a stack of items on either.
std::vector<const BrickType*> typesStandingAt(const std::vector<const BrickType*>& rivals,
                                              double height_above_support_m, const std::vector<double>& levels_m,
                                              const StackHeights& stacks, double tolerance_m);
}  // namespace brick_pose
