// A complete colour-free face placed at its catalogue size: the excess of
// its measured size comes off the edges its depth bounds.
#include <limits>

#include <gtest/gtest.h>

#include "brick_pose/roi/catalogue_size_placement.h"

namespace brick_pose
{
namespace
{
constexpr double kLengthM = 0.40, kWidthM = 0.30;
constexpr double kTrimLimitM = 0.03;

/// A face measured `length_m` x `width_m` centred on (0, 0, 1.5) m, long
/// axis along x, seen from above: corner 0 at (-L/2, -W/2), edge 0 (a long
/// edge) at y = -W/2, edge 1 at x = +L/2, edge 2 at y = +W/2, edge 3 at
/// x = -L/2.
std::array<Eigen::Vector3d, 4> face(double length_m, double width_m)
{
  const double x = 0.5 * length_m, y = 0.5 * width_m, z = 1.5;
  return {{Eigen::Vector3d(-x, -y, z), Eigen::Vector3d(x, -y, z), Eigen::Vector3d(x, y, z), Eigen::Vector3d(-x, y, z)}};
}

Eigen::Vector3d centreOf(const std::array<Eigen::Vector3d, 4>& corners)
{
  return 0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
}

EdgeKinds kinds(EdgeKind e0, EdgeKind e1, EdgeKind e2, EdgeKind e3) { return {{e0, e1, e2, e3}}; }

TEST(CatalogueSizePlacement, TheExcessComesOffTheEdgeDepthBoundsAndTheCentreMovesHalfOfIt)
{
  // 2 cm long past a step down at edge 1, whose opposite edge is a seam
  // between touching boxes; 1 cm wide past a step down at edge 2, across
  // from a colour line.
  const auto placed =
      cornersTrimmedToSize(face(kLengthM + 0.02, kWidthM + 0.01),
                           kinds(EdgeKind::kColourLine, EdgeKind::kStepDown, EdgeKind::kStepDown, EdgeKind::kSeam),
                           kLengthM, kWidthM, kTrimLimitM);
  EXPECT_NEAR(placed[1].x() - placed[0].x(), kLengthM, 1e-9);
  EXPECT_NEAR(placed[3].y() - placed[0].y(), kWidthM, 1e-9);
  // The seam and the line stay where they were.
  EXPECT_NEAR(placed[0].x(), -0.5 * (kLengthM + 0.02), 1e-9);
  EXPECT_NEAR(placed[0].y(), -0.5 * (kWidthM + 0.01), 1e-9);
  const Eigen::Vector3d centre = centreOf(placed);
  EXPECT_NEAR(centre.x(), -0.01, 1e-9);
  EXPECT_NEAR(centre.y(), -0.005, 1e-9);
  EXPECT_NEAR(centre.z(), 1.5, 1e-9);
}

TEST(CatalogueSizePlacement, EndsBoundAlikeShareTheExcessAndKeepTheCentre)
{
  for (const EdgeKind kind : {EdgeKind::kStepDown, EdgeKind::kColourLine})
  {
    const auto placed = cornersTrimmedToSize(face(kLengthM + 0.02, kWidthM + 0.01), kinds(kind, kind, kind, kind),
                                             kLengthM, kWidthM, kTrimLimitM);
    EXPECT_NEAR(placed[1].x() - placed[0].x(), kLengthM, 1e-9) << toString(kind);
    EXPECT_NEAR(placed[3].y() - placed[0].y(), kWidthM, 1e-9) << toString(kind);
    EXPECT_NEAR(centreOf(placed).norm(), 1.5, 1e-9) << toString(kind);
  }
}

TEST(CatalogueSizePlacement, BothEndsBoundByDepthShareTheExcessByWhereColourShowsThem)
{
  constexpr double kNotSeen = std::numeric_limits<double>::quiet_NaN();
  constexpr double kAgreementM = 0.002;
  const EdgeKinds steps = kinds(EdgeKind::kStepDown, EdgeKind::kStepDown, EdgeKind::kStepDown, EdgeKind::kCrease);
  const auto centreX = [&](double inset_1_m, double inset_3_m) {
    return centreOf(cornersTrimmedToSize(face(kLengthM + 0.02, kWidthM), steps, kLengthM, kWidthM, kTrimLimitM,
                                         {{kNotSeen, inset_1_m, kNotSeen, inset_3_m}}, kAgreementM))
        .x();
  };
  // Colour shows edge 1 (+x) 15 mm in and edge 3 6 mm in, together the 2 cm
  // excess within 2 mm: it comes off in that proportion.
  EXPECT_NEAR(centreX(0.015, 0.006), -0.5 * (0.02 * 15.0 / 21.0 - 0.02 * 6.0 / 21.0), 1e-9);
  // Ends that disagree with the excess (15 mm and 0: print by an edge?) are
  // not trusted: half each.
  EXPECT_NEAR(centreX(0.015, 0.0), 0.0, 1e-9);
  // Only edge 1 seen, 12 mm in: that much off it, the other 8 mm off edge 3.
  EXPECT_NEAR(centreX(0.012, kNotSeen), -0.002, 1e-9);
  // One end seen farther in than the excess is not trusted either.
  EXPECT_NEAR(centreX(kNotSeen, 0.03), 0.0, 1e-9);
  // Neither seen: half each.
  EXPECT_NEAR(centreX(kNotSeen, kNotSeen), 0.0, 1e-9);
  // Colour is only asked where both ends are bound by depth: beside a seam
  // the step down takes it all whatever colour says.
  const EdgeKinds one_step = kinds(EdgeKind::kStepDown, EdgeKind::kStepDown, EdgeKind::kStepDown, EdgeKind::kSeam);
  EXPECT_NEAR(centreOf(cornersTrimmedToSize(face(kLengthM + 0.02, kWidthM), one_step, kLengthM, kWidthM, kTrimLimitM,
                                            {{kNotSeen, 0.001, kNotSeen, 0.019}}, kAgreementM))
                  .x(),
              -0.01, 1e-9);
}

TEST(CatalogueSizePlacement, AFaceNoLongerThanItsTypeStaysAndTheTrimIsBounded)
{
  const EdgeKinds one_side = kinds(EdgeKind::kStepDown, EdgeKind::kCrease, EdgeKind::kSeam, EdgeKind::kStepUp);
  const auto short_face = face(kLengthM - 0.01, kWidthM);
  const auto unchanged = cornersTrimmedToSize(short_face, one_side, kLengthM, kWidthM, kTrimLimitM);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR((unchanged[k] - short_face[k]).norm(), 0.0, 1e-12) << "corner " << k;
  // 5 cm too long: only the limit comes off (the crease at edge 1).
  const auto long_face = cornersTrimmedToSize(face(kLengthM + 0.05, kWidthM), one_side, kLengthM, kWidthM, kTrimLimitM);
  EXPECT_NEAR(long_face[1].x() - long_face[0].x(), kLengthM + 0.05 - kTrimLimitM, 1e-9);
  EXPECT_NEAR(long_face[0].x(), -0.5 * (kLengthM + 0.05), 1e-9);
}

TEST(CatalogueSizePlacement, OnlyStepsDownCreasesAndDropsBesideWallsAreBoundByDepth)
{
  for (const EdgeKind kind : {EdgeKind::kStepDown, EdgeKind::kCrease, EdgeKind::kDropBesideWall})
    EXPECT_TRUE(depthBoundsEdge(kind)) << toString(kind);
  for (const EdgeKind kind : {EdgeKind::kSeam, EdgeKind::kColourLine, EdgeKind::kSizePlacedLine, EdgeKind::kStepUp,
                              EdgeKind::kOcclusion, EdgeKind::kImageBorder, EdgeKind::kMaskEdge})
    EXPECT_FALSE(depthBoundsEdge(kind)) << toString(kind);
}
}  // namespace
}  // namespace brick_pose
