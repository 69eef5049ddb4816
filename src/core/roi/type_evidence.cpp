#include "brick_pose/roi/type_evidence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "brick_pose/catalogue/resting.h"

namespace brick_pose
{
namespace
{
double topErrorM(const BrickType& type, double length_m, double width_m)
{
  return std::abs(length_m - type.length_m) + std::abs(width_m - type.width_m);
}

/// How far a type is from what is seen (m): its top against the face's
/// size, and its height against every side that reaches the supporting
/// plane (which measures the height).
double typeErrorM(const BrickType& type, double length_m, double width_m, const std::vector<SideFaceEvidence>& sides)
{
  double error_m = topErrorM(type, length_m, width_m);
  for (const SideFaceEvidence& side : sides)
    if (side.foot_on_support) error_m += std::abs(side.visible_height_m - type.height_m);
  return error_m;
}

/// closestType()'s misfit of one type (m), without where it stands.
double typeMisfitM(const BrickType& type, double length_m, double width_m, const std::vector<SideFaceEvidence>& sides)
{
  double error_m = topErrorM(type, length_m, width_m);
  for (const SideFaceEvidence& side : sides)
  {
    error_m += side.foot_on_support ? std::abs(side.visible_height_m - type.height_m)
                                    : std::max(0.0, side.visible_height_m - type.height_m);
    // A type taller than a side ending on something needs the rest of
    // its side hidden there by a neighbour just that high: among types
    // otherwise tied, the one the side ends at the bottom of is likelier.
    if (!side.foot_on_support && type.height_m > side.visible_height_m + kTypeMarginM)
      error_m += kHiddenSidePenaltyM;
  }
  return error_m;
}

bool ruledOut(const BrickType& rival, const BrickType& best, double length_m, double width_m,
              const std::vector<SideFaceEvidence>& sides, const SideFaceParams& params, bool rival_on_support_alone)
{
  if (typeErrorM(rival, length_m, width_m, sides) - typeErrorM(best, length_m, width_m, sides) >= kTypeMarginM)
    return true;
  if (!rival_on_support_alone) return false;
  return std::any_of(sides.begin(), sides.end(), [&](const SideFaceEvidence& side) {
    return !side.foot_on_support && judgeSideFace(side, rival.height_m, params) == SideFaceVerdict::kMismatch;
  });
}

/// Two cuboids within kTypeMarginM in every dimension: taking one for the
/// other leaves the pose and the size within the measurement's error.
bool sameShape(const BrickType& a, const BrickType& b)
{
  return std::abs(a.length_m - b.length_m) < kTypeMarginM && std::abs(a.width_m - b.width_m) < kTypeMarginM &&
         std::abs(a.height_m - b.height_m) < kTypeMarginM;
}
}  // namespace

bool showsTop(const BrickType& type, double length_m, double width_m, double tolerance_m)
{
  return std::abs(length_m - type.length_m) <= tolerance_m && std::abs(width_m - type.width_m) <= tolerance_m;
}

const BrickType* closestType(const std::vector<const BrickType*>& fitting, double length_m, double width_m,
                             const std::vector<SideFaceEvidence>& sides, const std::vector<double>& standing_misfits_m,
                             double* misfit_m)
{
  const BrickType* best = nullptr;
  double best_error_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < fitting.size(); ++i)
  {
    const BrickType& type = *fitting[i];
    double error_m = typeMisfitM(type, length_m, width_m, sides);
    if (i < standing_misfits_m.size()) error_m += standing_misfits_m[i];
    if (!best || error_m < best_error_m)  // (a NaN error never wins)
    {
      best = &type;
      best_error_m = error_m;
    }
  }
  if (misfit_m) *misfit_m = best_error_m;
  return best;
}

std::vector<BrickType> lyingVariants(const std::vector<BrickType>& types)
{
  std::vector<BrickType> variants;
  for (const BrickType& type : types)
    for (const Resting resting : {Resting::kOnSide, Resting::kOnEnd})
    {
      BrickType variant = restingAs(type, resting);
      if (topErrorM(variant, type.length_m, type.width_m) >= kTypeMarginM) variants.push_back(variant);
    }
  return variants;
}

std::vector<const BrickType*> rivalsInDoubt(const std::vector<const BrickType*>& rivals, const BrickType& best,
                                            double length_m, double width_m,
                                            const std::vector<SideFaceEvidence>& sides, const SideFaceParams& params,
                                            const std::vector<const BrickType*>& on_support_alone)
{
  std::vector<const BrickType*> open;
  for (const BrickType* type : rivals)
  {
    const bool alone = std::find(on_support_alone.begin(), on_support_alone.end(), type) != on_support_alone.end();
    if (type != &best && !sameShape(*type, best) && !ruledOut(*type, best, length_m, width_m, sides, params, alone))
      open.push_back(type);
  }
  return open;
}

std::string typeDoubtText(const BrickType& best, const std::vector<const BrickType*>& open)
{
  if (open.empty()) return {};
  std::string others;
  for (const BrickType* type : open) others += (others.empty() ? "" : ", ") + type->name;
  return "type uncertain: the face fits " + best.name + " and " + others +
         ", and no side seen tells their heights apart";
}

std::string typeDoubt(const std::vector<const BrickType*>& rivals, const BrickType& best, double length_m,
                      double width_m, const std::vector<SideFaceEvidence>& sides, const SideFaceParams& params,
                      const std::vector<const BrickType*>& on_support_alone)
{
  return typeDoubtText(best, rivalsInDoubt(rivals, best, length_m, width_m, sides, params, on_support_alone));
}

StackHeights::StackHeights(const std::vector<double>& item_heights_m, double max_height_m, double resolution_m)
  : resolution_m_(resolution_m),
    items_(static_cast<std::size_t>(std::ceil(max_height_m / resolution_m)) + 1, kUnmakeable)
{
  std::vector<std::size_t> steps;
  for (const double height_m : item_heights_m)
    if (height_m > 0.0) steps.push_back(static_cast<std::size_t>(std::max(1.0, std::round(height_m / resolution_m))));
  // Unbounded knapsack, fewest items: a height takes one item more than
  // the height one item less.
  items_[0] = 0;
  for (std::size_t k = 1; k < items_.size(); ++k)
    for (const std::size_t step : steps)
      if (step <= k && items_[k - step] != kUnmakeable)
        items_[k] = std::min<std::uint8_t>(items_[k], static_cast<std::uint8_t>(std::min(254, items_[k - step] + 1)));
}

StackHeights StackHeights::of(const std::vector<BrickType>& types)
{
  std::vector<double> heights_m;
  for (const BrickType& type : types)
    heights_m.insert(heights_m.end(), {type.height_m, type.width_m, type.length_m});
  return StackHeights(heights_m);
}

bool StackHeights::canMake(double height_m, double tolerance_m) const
{
  if (!std::isfinite(height_m)) return false;
  const double last_m = static_cast<double>(items_.size() - 1) * resolution_m_;
  if (height_m - tolerance_m > last_m) return true;
  const long first = std::max(0L, static_cast<long>(std::ceil((height_m - tolerance_m) / resolution_m_)));
  const long last = std::min(static_cast<long>(items_.size()) - 1,
                             static_cast<long>(std::floor((height_m + tolerance_m) / resolution_m_)));
  for (long k = first; k <= last; ++k)
    if (items_[static_cast<std::size_t>(k)] != kUnmakeable) return true;
  return false;
}

double StackHeights::misfitM(double height_m, double per_item_m) const
{
  if (!std::isfinite(height_m)) return std::numeric_limits<double>::infinity();
  const long last = static_cast<long>(items_.size()) - 1;
  if (height_m > static_cast<double>(last) * resolution_m_) return 0.0;
  if (height_m <= 0.0) return -height_m;  // nothing below: the support itself
  // Outward from the nearest grid height, until the distance alone is
  // no better than the best found.
  const long nearest = std::clamp(static_cast<long>(std::lround(height_m / resolution_m_)), 0L, last);
  double best_m = std::numeric_limits<double>::infinity();
  for (long step = 0; step <= last; ++step)
  {
    if (static_cast<double>(step - 1) * resolution_m_ >= best_m) break;
    for (const long k : {nearest - step, nearest + step})
    {
      if (k < 0 || k > last || items_[static_cast<std::size_t>(k)] == kUnmakeable) continue;
      const double misfit_m =
          std::abs(height_m - static_cast<double>(k) * resolution_m_) + per_item_m * items_[static_cast<std::size_t>(k)];
      best_m = std::min(best_m, misfit_m);
    }
  }
  return best_m;
}

double standingMisfitM(const BrickType& type, double height_above_support_m, const StackHeights& stacks)
{
  return stacks.misfitM(height_above_support_m - type.height_m, kStackItemPenaltyM);
}

std::vector<double> standingMisfitsM(const std::vector<const BrickType*>& types, double height_above_support_m,
                                     const StackHeights& stacks)
{
  std::vector<double> misfits_m;
  for (const BrickType* type : types) misfits_m.push_back(standingMisfitM(*type, height_above_support_m, stacks));
  return misfits_m;
}

double footingUnseenPenaltyM(const BrickType& type, double height_above_support_m,
                             const std::vector<double>& levels_m, double tolerance_m)
{
  const double below_m = height_above_support_m - type.height_m;
  const bool seen = std::abs(below_m) <= tolerance_m ||
                    std::any_of(levels_m.begin(), levels_m.end(),
                                [&](double level_m) { return std::abs(level_m - below_m) <= tolerance_m; });
  return seen ? 0.0 : kFootingUnseenPenaltyM;
}

bool standsOnSupportAlone(const BrickType& type, double height_above_support_m, const std::vector<double>& levels_m,
                          double tolerance_m)
{
  const double below_m = height_above_support_m - type.height_m;
  return below_m <= tolerance_m && std::all_of(levels_m.begin(), levels_m.end(), [&](double level_m) {
           return level_m > below_m + tolerance_m;
         });
}

std::vector<const BrickType*> typesOnSupportAlone(const std::vector<const BrickType*>& rivals,
                                                  double height_above_support_m, const std::vector<double>& levels_m,
                                                  double tolerance_m)
{
  std::vector<const BrickType*> alone;
  for (const BrickType* type : rivals)
    if (standsOnSupportAlone(*type, height_above_support_m, levels_m, tolerance_m)) alone.push_back(type);
  return alone;
}

std::vector<const BrickType*> typesStandingAt(const std::vector<const BrickType*>& rivals,
                                              double height_above_support_m, const std::vector<double>& levels_m,
                                              const StackHeights& stacks, double tolerance_m)
{
  std::vector<const BrickType*> standing;
  for (const BrickType* type : rivals)
  {
    const double below_m = height_above_support_m - type->height_m;
    bool can_stand = stacks.canMake(below_m, tolerance_m);
    for (const double level_m : levels_m) can_stand = can_stand || stacks.canMake(below_m - level_m, tolerance_m);
    if (can_stand) standing.push_back(type);
  }
  return standing;
}
}  // namespace brick_pose
