// Telling catalogue types apart by a face's size and the heights of its
// sides: which rivals the evidence rules out, and which it leaves in doubt.
#include <cmath>

#include <gtest/gtest.h>

#include "brick_pose/roi/type_evidence.h"
#include "plain_box.h"

namespace brick_pose
{
namespace
{
SideFaceEvidence side(double height_m, bool on_support)
{
  SideFaceEvidence evidence;
  evidence.visible = true;
  evidence.foot_seen = true;
  evidence.foot_on_support = on_support;
  evidence.visible_height_m = height_m;
  return evidence;
}

const BrickType kSmall = plainBox("box_small", 0.30, 0.20, 0.15);
const BrickType kFlat = plainBox("box_flat", 0.30, 0.20, 0.07);

TEST(TypeEvidence, OneTopTwoHeightsIsADoubtUntilASideReachesTheSupport)
{
  const std::vector<const BrickType*> rivals{&kSmall, &kFlat};
  // No side seen: the closest by size is a guess.
  const std::string doubt = typeDoubt(rivals, kSmall, 0.30, 0.20, {});
  EXPECT_NE(doubt.find("type uncertain"), std::string::npos);
  EXPECT_NE(doubt.find("box_flat"), std::string::npos) << doubt;
  // A side 0.15 m down to the ground measures the height.
  EXPECT_EQ(closestType(rivals, 0.30, 0.20, {side(0.15, true)}), &kSmall);
  EXPECT_TRUE(typeDoubt(rivals, kSmall, 0.30, 0.20, {side(0.15, true)}).empty());
  EXPECT_EQ(closestType(rivals, 0.30, 0.20, {side(0.07, true)}), &kFlat);
  EXPECT_TRUE(typeDoubt(rivals, kFlat, 0.30, 0.20, {side(0.07, true)}).empty());
  // A side ending 0.10 m down on something above the support is taller
  // than the flat box: its side and, flush below it, that of a box it
  // stands on. Only a flat box that could stand on nothing but the support
  // is out; the small one is then certain.
  EXPECT_FALSE(typeDoubt(rivals, kSmall, 0.30, 0.20, {side(0.10, false)}).empty());
  EXPECT_TRUE(typeDoubt(rivals, kSmall, 0.30, 0.20, {side(0.10, false)}, SideFaceParams(), {&kFlat}).empty());
  // Ending 0.05 m down rules nothing out.
  EXPECT_FALSE(typeDoubt(rivals, kSmall, 0.30, 0.20, {side(0.05, false)}, SideFaceParams(), {&kFlat}).empty());
}

TEST(TypeEvidence, TheRivalsLeftOpenAreTheOnesTheDoubtNames)
{
  const BrickType tall = plainBox("box_tall", 0.30, 0.20, 0.40);
  const std::vector<const BrickType*> rivals{&kSmall, &kFlat, &tall};
  // No side seen: both other heights stay open, in the rivals' order.
  const std::vector<const BrickType*> open = rivalsInDoubt(rivals, kSmall, 0.30, 0.20, {});
  ASSERT_EQ(open.size(), 2u);
  EXPECT_EQ(open[0], &kFlat);
  EXPECT_EQ(open[1], &tall);
  EXPECT_EQ(typeDoubtText(kSmall, open), typeDoubt(rivals, kSmall, 0.30, 0.20, {}));
  // A side 0.15 m down to the support rules both out.
  EXPECT_TRUE(rivalsInDoubt(rivals, kSmall, 0.30, 0.20, {side(0.15, true)}).empty());
  EXPECT_TRUE(typeDoubtText(kSmall, {}).empty());
  // A side ending 0.10 m down on something: the flat box may stand on a
  // box beneath it unless it can stand on the support alone; the tall one
  // stays open (the rest of its side hidden by a neighbour).
  const std::vector<const BrickType*> on_something = rivalsInDoubt(rivals, kSmall, 0.30, 0.20, {side(0.10, false)},
                                                                   SideFaceParams(), {&kFlat});
  ASSERT_EQ(on_something.size(), 1u);
  EXPECT_EQ(on_something[0], &tall);
}

TEST(TypeEvidence, ATypeStandsOnTheSupportAloneWhenNothingFitsBeneathIt)
{
  const double tolerance_m = 0.025;
  // A top 0.07 m up: a flat box on the support; a top 0.15 m up: a tall box
  // on it, or a flat box on something 0.08 m high.
  EXPECT_TRUE(standsOnSupportAlone(kFlat, 0.07, {}, tolerance_m));
  EXPECT_TRUE(standsOnSupportAlone(kSmall, 0.15, {}, tolerance_m));
  EXPECT_FALSE(standsOnSupportAlone(kFlat, 0.15, {}, tolerance_m));
  // A level seen 0.01 m up around the foot (a mat) may be under it.
  EXPECT_FALSE(standsOnSupportAlone(kSmall, 0.16, {0.01}, tolerance_m));
  EXPECT_TRUE(standsOnSupportAlone(kSmall, 0.15, {0.08}, tolerance_m));
}

TEST(TypeEvidence, ASideEndingAboveTheSupportIsALowerBoundNotTheHeight)
{
  const std::vector<const BrickType*> fitting{&kSmall, &kFlat};
  // A tall box beside a lower one shows only part of its side, down to the
  // lower top (3 cm of it on the rig's pallet frame 136): nearer the flat
  // box's 0.07 than the tall one's 0.15, but either could show it. Neither
  // is favoured: the first listed stays the guess (read as the height, 3 cm
  // made the flat box the guess).
  EXPECT_EQ(closestType(fitting, 0.30, 0.20, {side(0.03, false)}), &kSmall);
  // (A tie keeps the order given.)
  EXPECT_EQ(closestType({&kFlat, &kSmall}, 0.30, 0.20, {side(0.06, false)}), &kFlat);
  // Taller than a type, it counts against that type (a tall box beside a
  // flat one shows 0.08 m).
  EXPECT_EQ(closestType({&kFlat, &kSmall}, 0.30, 0.20, {side(0.08, false)}), &kSmall);
  // Down to the support, it is the height.
  EXPECT_EQ(closestType(fitting, 0.30, 0.20, {side(0.08, true)}), &kFlat);
}

TEST(TypeEvidence, AmongEqualFitsTheTypeStandingExactlyAtTheFacesHeightOnFewestItemsWins)
{
  const StackHeights stacks = StackHeights::of({kSmall, kFlat});
  // 0.15 m above the support: a tall box on it (exact, nothing beneath), or
  // a flat box on another (0.14 m: 1 cm off, one item beneath).
  EXPECT_NEAR(standingMisfitM(kSmall, 0.15, stacks), 0.0, 1e-9);
  EXPECT_NEAR(standingMisfitM(kFlat, 0.15, stacks), 0.01 + kStackItemPenaltyM, 1e-3);
  const std::vector<const BrickType*> flat_first{&kFlat, &kSmall};
  EXPECT_EQ(closestType(flat_first, 0.30, 0.20, {},
                        {standingMisfitM(kFlat, 0.15, stacks), standingMisfitM(kSmall, 0.15, stacks)}),
            &kSmall);
  // 0.07 m up only a flat box stands; below the support nothing does, by
  // how far it would sink.
  EXPECT_NEAR(standingMisfitM(kFlat, 0.07, stacks), 0.0, 1e-9);
  EXPECT_NEAR(standingMisfitM(kSmall, 0.07, stacks), 0.08, 1e-9);
  // High up, almost any height is some stack's: a top 0.549 m up is a tall
  // box on a large one standing on an end (0.40 m, one item, 1 mm off), or
  // a flat box on a large one and a flat one (0.47 m, two items, 9 mm off)
  // or on five items (0.20 + 4 x 0.07, 1 mm off). The fewest items win.
  const StackHeights boxes = StackHeights::of({plainBox("box_large", 0.40, 0.30, 0.25), kSmall, kFlat});
  EXPECT_LT(standingMisfitM(kSmall, 0.549, boxes), standingMisfitM(kFlat, 0.549, boxes));
  // A side's misfit and the standing misfit add up.
  EXPECT_EQ(closestType(flat_first, 0.30, 0.20, {side(0.15, true)}, {0.0, 0.01}), &kSmall);
}

TEST(TypeEvidence, ASideEndingAtATypesOwnHeightBreaksATieOfStandingMisfits)
{
  // A top 0.22 m up on a stack: a flat box on a tall one or a tall box on a
  // flat one, each on one item, exactly: the standing misfits tie.
  const StackHeights stacks = StackHeights::of({kSmall, kFlat});
  const std::vector<double> misfits_m{standingMisfitM(kSmall, 0.22, stacks), standingMisfitM(kFlat, 0.22, stacks)};
  ASSERT_NEAR(misfits_m[0], misfits_m[1], 1e-9);
  const std::vector<const BrickType*> small_first{&kSmall, &kFlat};
  // Nothing seen: the order given decides.
  EXPECT_EQ(closestType(small_first, 0.30, 0.20, {}, misfits_m), &kSmall);
  // A side 0.07 m tall ending on a ledge: the flat box's whole side on the
  // box beneath, or a tall box's upper half over a neighbour exactly that
  // high. The flat box is the likelier, in either order.
  EXPECT_EQ(closestType(small_first, 0.30, 0.20, {side(0.07, false)}, misfits_m), &kFlat);
  EXPECT_EQ(closestType({&kFlat, &kSmall}, 0.30, 0.20, {side(0.07, false)}, {misfits_m[1], misfits_m[0]}), &kFlat);
  // A side 0.15 m tall is more than a flat box has.
  EXPECT_EQ(closestType({&kFlat, &kSmall}, 0.30, 0.20, {side(0.15, false)}, {misfits_m[1], misfits_m[0]}), &kSmall);
  // The tie-break is less than an item beneath: a tall box exactly on the
  // support still beats a flat one on an item (0.15 m up).
  EXPECT_EQ(closestType({&kFlat, &kSmall}, 0.30, 0.20, {side(0.07, false)},
                        {standingMisfitM(kFlat, 0.15, stacks), standingMisfitM(kSmall, 0.15, stacks)}),
            &kSmall);
  // And the doubt stays: the evidence rules neither out.
  EXPECT_FALSE(typeDoubt(small_first, kFlat, 0.30, 0.20, {side(0.07, false)}).empty());
}

TEST(TypeEvidence, ALevelSeenWhereATypeWouldStandBreaksATieOfStandingMisfits)
{
  // The same tie, 0.22 m up: a lower box's top seen beside the face at
  // 0.15 m is where a flat box stands; at 0.07 m, where a tall one does.
  const StackHeights stacks = StackHeights::of({kSmall, kFlat});
  const double height_m = 0.22, tolerance_m = 0.02;
  auto misfits = [&](const std::vector<double>& levels_m) {
    return std::vector<double>{
        standingMisfitM(kSmall, height_m, stacks) + footingUnseenPenaltyM(kSmall, height_m, levels_m, tolerance_m),
        standingMisfitM(kFlat, height_m, stacks) + footingUnseenPenaltyM(kFlat, height_m, levels_m, tolerance_m)};
  };
  const std::vector<const BrickType*> small_first{&kSmall, &kFlat};
  EXPECT_EQ(closestType(small_first, 0.30, 0.20, {}, misfits({0.148})), &kFlat);
  EXPECT_EQ(closestType(small_first, 0.30, 0.20, {}, misfits({0.072})), &kSmall);
  // Both footings seen, or neither: the order given decides, as before.
  EXPECT_EQ(closestType(small_first, 0.30, 0.20, {}, misfits({0.072, 0.148})), &kSmall);
  EXPECT_EQ(closestType(small_first, 0.30, 0.20, {}, misfits({0.11})), &kSmall);
  // Standing on the support needs no level.
  EXPECT_EQ(footingUnseenPenaltyM(kSmall, 0.15, {}, tolerance_m), 0.0);
  EXPECT_EQ(footingUnseenPenaltyM(kFlat, 0.15, {}, tolerance_m), kFootingUnseenPenaltyM);
  // Less than an item beneath: a tall box exactly on the support beats a
  // flat one on an item whose footing shows (0.15 m up, a level at 0.08 m).
  EXPECT_EQ(closestType({&kFlat, &kSmall}, 0.30, 0.20, {},
                        {standingMisfitM(kFlat, 0.15, stacks) + footingUnseenPenaltyM(kFlat, 0.15, {0.08}, tolerance_m),
                         standingMisfitM(kSmall, 0.15, stacks)}),
            &kSmall);
  // And less than a hidden side's: it only names the likelier of a tie.
  EXPECT_LT(kFootingUnseenPenaltyM, kHiddenSidePenaltyM);
}

TEST(TypeEvidence, NearlyEqualFitsLeaveADoubtAndClearOnesDoNot)
{
  const BrickType upright = plainBox("upright", 0.128, 0.038, 0.212);
  const BrickType other = plainBox("other", 0.147, 0.054, 0.243);
  const std::vector<const BrickType*> rivals{&upright, &other};
  // Measured 1 cm wide: as near the other's top as its own.
  EXPECT_FALSE(typeDoubt(rivals, upright, 0.133, 0.048, {}).empty());
  // Measured to 2 mm: the other fits 31 mm worse.
  EXPECT_TRUE(typeDoubt(rivals, upright, 0.129, 0.040, {}).empty());
  // The side down to the table adds 31 mm against the other over its 6 mm.
  EXPECT_TRUE(typeDoubt(rivals, upright, 0.133, 0.048, {side(0.218, true)}).empty());
}

TEST(TypeEvidence, BoxesOfOneShapeWithinTheMarginAreNoDoubt)
{
  const BrickType a = plainBox("a", 0.195, 0.047, 0.267);
  const BrickType b = plainBox("b", 0.204, 0.047, 0.255);
  EXPECT_TRUE(typeDoubt({&a, &b}, a, 0.200, 0.047, {}).empty());
}

TEST(TypeEvidence, LyingVariantsAreTheFacesThatDifferFromTheTop)
{
  // A 0.40 x 0.30 x 0.25 m box: on a side it shows 0.40 x 0.25 (0.30 tall),
  // on an end 0.30 x 0.25 (0.40 tall).
  const std::vector<BrickType> large = lyingVariants({plainBox("large", 0.40, 0.30, 0.25)});
  ASSERT_EQ(large.size(), 2u);
  EXPECT_EQ(large[0].name, "large lying on a side");
  EXPECT_DOUBLE_EQ(large[0].length_m, 0.40);
  EXPECT_DOUBLE_EQ(large[0].width_m, 0.25);
  EXPECT_DOUBLE_EQ(large[0].height_m, 0.30);
  EXPECT_EQ(large[1].name, "large standing on an end");
  EXPECT_DOUBLE_EQ(large[1].length_m, 0.30);
  EXPECT_DOUBLE_EQ(large[1].width_m, 0.25);
  EXPECT_DOUBLE_EQ(large[1].height_m, 0.40);
  // A brick 0.2 x 0.2 in section shows its top's size on its side: only the
  // end differs.
  const std::vector<BrickType> red = lyingVariants({plainBox("red", 0.30, 0.20, 0.20)});
  ASSERT_EQ(red.size(), 1u);
  EXPECT_EQ(red[0].name, "red standing on an end");

  // A crate whose side face is near its top's size: a face measured between
  // the two is a doubt, even with a side (0.28 vs 0.30 m tall); a top
  // measured at its size with its side 0.28 m down to the ground is not.
  const BrickType crate = plainBox("crate", 0.40, 0.30, 0.28);
  const std::vector<BrickType> lying = lyingVariants({crate});
  const std::vector<const BrickType*> rivals{&crate, &lying[0]};
  EXPECT_NE(typeDoubt(rivals, crate, 0.40, 0.285, {}).find("crate lying on a side"), std::string::npos);
  EXPECT_FALSE(typeDoubt(rivals, crate, 0.40, 0.285, {side(0.28, true)}).empty());
  EXPECT_TRUE(typeDoubt(rivals, crate, 0.40, 0.30, {side(0.28, true)}).empty());
}

TEST(StackHeights, AnyNumberOfItemsInAnyOrderMakeAHeight)
{
  const StackHeights stacks({0.07, 0.15});
  EXPECT_TRUE(stacks.canMake(0.0, 0.005)) << "nothing beneath: standing on the support";
  EXPECT_TRUE(stacks.canMake(0.14, 0.002)) << "two flat boxes";
  EXPECT_TRUE(stacks.canMake(0.22, 0.002)) << "a flat box on a tall one";
  EXPECT_TRUE(stacks.canMake(0.07 * 5 + 0.15 * 3, 0.002)) << "eight boxes";
  EXPECT_FALSE(stacks.canMake(0.10, 0.02)) << "no stack is 0.08-0.12 m";
  EXPECT_TRUE(stacks.canMake(0.10, 0.03)) << "0.07 is within 0.03 of it";
  EXPECT_FALSE(stacks.canMake(-0.05, 0.02)) << "below the support";
  EXPECT_TRUE(stacks.canMake(-0.01, 0.02));
  EXPECT_FALSE(stacks.canMake(std::nan(""), 0.02));
  EXPECT_TRUE(StackHeights({0.07}, 1.0).canMake(5.0, 0.01)) << "beyond the heights it knows, anything may be";
  EXPECT_NEAR(stacks.misfitM(0.10), 0.03, 1e-9) << "0.07 is the nearest stack";
  EXPECT_NEAR(stacks.misfitM(0.2205), 0.0005, 1e-9);
  EXPECT_NEAR(stacks.misfitM(0.2205, 0.01), 0.0205, 1e-9) << "two items";
  EXPECT_NEAR(stacks.misfitM(0.145, 0.01), 0.015, 1e-9) << "one item 5 mm off beats two 5 mm off";
  EXPECT_NEAR(stacks.misfitM(0.142, 0.01), 0.018, 1e-9) << "one item 8 mm off beats two 2 mm off";
  EXPECT_TRUE(std::isinf(stacks.misfitM(std::nan(""))));
  EXPECT_NEAR(stacks.misfitM(-0.02), 0.02, 1e-9) << "below the support";
  EXPECT_EQ(StackHeights({0.07}, 1.0).misfitM(5.0), 0.0);
}

TEST(StackHeights, ABoxLyingOnASideOrStandingOnAnEndStacksToo)
{
  // A 0.30 x 0.20 x 0.07 box makes 0.07, 0.20 and 0.30 m.
  const StackHeights stacks = StackHeights::of({kFlat});
  EXPECT_TRUE(stacks.canMake(0.20, 0.002));
  EXPECT_TRUE(stacks.canMake(0.30, 0.002));
  EXPECT_TRUE(stacks.canMake(0.27, 0.002));
  EXPECT_FALSE(stacks.canMake(0.10, 0.02));
}

TEST(StackHeights, AFacesHeightAboveTheSupportRulesOutTheTypesThatCannotStandThere)
{
  const StackHeights stacks = StackHeights::of({kSmall, kFlat});
  const std::vector<const BrickType*> rivals{&kSmall, &kFlat};
  const double tolerance_m = 0.025;
  // On the ground: only the flat box's top is 0.07 m up.
  EXPECT_EQ(typesStandingAt(rivals, 0.07, {}, stacks, tolerance_m), std::vector<const BrickType*>{&kFlat});
  // 0.15 m: a tall box, or a flat one on a flat one (0.14 m).
  EXPECT_EQ(typesStandingAt(rivals, 0.15, {}, stacks, tolerance_m).size(), 2u);
  // 0.17 m: a tall box on the ground (0.02 off), not a flat one: 0.10 m
  // beneath it is no stack ...
  EXPECT_EQ(typesStandingAt(rivals, 0.17, {}, stacks, tolerance_m), std::vector<const BrickType*>{&kSmall});
  // ... unless it stands on a plinth 0.10 m high seen around it.
  EXPECT_EQ(typesStandingAt(rivals, 0.17, {0.10}, stacks, tolerance_m).size(), 2u);
  // Below both: nothing could stand there.
  EXPECT_TRUE(typesStandingAt(rivals, 0.03, {}, stacks, tolerance_m).empty());
}

}  // namespace
}  // namespace brick_pose
