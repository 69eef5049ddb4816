// Edge evidence: what lies beyond a face's edge, on synthetic depth/colour
// profiles with the noise of a real sensor.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "brick_pose/common/errors.h"
#include "brick_pose/frame/frame_builder.h"
#include "brick_pose/roi/edge_evidence.h"

namespace brick_pose
{
namespace
{
constexpr int kWidth = 320, kHeight = 240;
constexpr double kFaceDepthM = 1.2;
constexpr double kEdgeU = 160.0;  // the face covers u < kEdgeU; the edge runs top to bottom

PinholeCamera camera()
{
  PinholeCamera c;
  c.width_px = kWidth;
  c.height_px = kHeight;
  c.fx_px = c.fy_px = 300.0;
  c.cx_px = 159.5;
  c.cy_px = 119.5;
  return c;
}

/// The face: a fronto-parallel plane at kFaceDepthM, fitted with `rms_m`.
PlaneFit facePlane(double rms_m = 0.0015)
{
  PlaneFit plane;
  plane.centroid_m = Eigen::Vector3d(0.0, 0.0, kFaceDepthM);
  plane.normal = -Eigen::Vector3d::UnitZ();
  plane.rms_m = rms_m;
  plane.valid = true;
  return plane;
}

/// A frame whose depth and grey level at each pixel come from the given
/// functions (depth NaN = no depth), plus white noise of `noise_m` and 3
/// grey levels.
RgbdFrame makeFrame(const std::function<double(int, int)>& depth_m, const std::function<double(int, int)>& grey,
                    double noise_m = 0.0015, unsigned seed = 7)
{
  std::mt19937 generator(seed);
  std::normal_distribution<double> depth_noise(0.0, noise_m), grey_noise(0.0, 3.0);
  cv::Mat rgb(kHeight, kWidth, CV_8UC3), depth(kHeight, kWidth, CV_32FC1);
  for (int v = 0; v < kHeight; ++v)
    for (int u = 0; u < kWidth; ++u)
    {
      const double z = depth_m(u, v);
      depth.at<float>(v, u) = std::isnan(z) ? std::nanf("") : static_cast<float>(z + depth_noise(generator));
      const auto level = cv::saturate_cast<std::uint8_t>(grey(u, v) + grey_noise(generator));
      rgb.at<cv::Vec3b>(v, u) = cv::Vec3b(level, level, level);
    }
  FrameHeader header;
  header.stamp_ns = 1;
  header.frame_id = "test";
  return makeRgbdFrame(rgb, depth, camera(), header);
}

double plainGrey(int, int) { return 150.0; }

EdgeKind classify(const RgbdFrame& frame, double edge_u = kEdgeU, double plane_rms_m = 0.0015)
{
  // The edge from (edge_u, 30) to (edge_u, 210); outward is +u.
  return classifyEdge(frame, facePlane(plane_rms_m), Eigen::Vector2d(edge_u, 30.0), Eigen::Vector2d(edge_u, 210.0),
                      Eigen::Vector2d(1.0, 0.0))
      .kind;
}

TEST(EdgeEvidence, StepDownToAFartherSurfaceIsARealEdge)
{
  const RgbdFrame frame = makeFrame([](int u, int) { return u < kEdgeU ? kFaceDepthM : kFaceDepthM + 0.2; }, plainGrey);
  EXPECT_EQ(classify(frame), EdgeKind::kStepDown);
  EXPECT_TRUE(isRealEdge(EdgeKind::kStepDown));
}

TEST(EdgeEvidence, AStereoShadowBeyondTheStepStillShowsTheStep)
{
  // D4xx: the first pixels beyond a step have no depth (the other imager
  // cannot see them), the background appears further out.
  const RgbdFrame frame = makeFrame(
      [](int u, int) {
        if (u < kEdgeU) return kFaceDepthM;
        return u < kEdgeU + 9 ? std::nan("") : kFaceDepthM + 0.2;
      },
      plainGrey);
  EXPECT_EQ(classify(frame), EdgeKind::kStepDown);
}

TEST(EdgeEvidence, SideFaceBendingAwayIsACrease)
{
  // Beyond the edge the surface turns away from the camera (the brick's
  // own side seen obliquely): continuous at the edge, ever farther beyond.
  const RgbdFrame frame = makeFrame(
      [](int u, int) { return u < kEdgeU ? kFaceDepthM : kFaceDepthM + 0.01 * (u - kEdgeU); }, plainGrey);
  EXPECT_EQ(classify(frame), EdgeKind::kCrease);
}

/// A far face in VGA: 4 mm of noise per pixel, a plane fitted with 6 mm rms
/// (a row of the profile must clear 2.4 cm to count as another surface).
/// Beyond the edge the stereo window holds the top's depth for 2 pixels,
/// then the surface falls `slope_m_per_px` per pixel.
RgbdFrame farFaceFalling(double slope_m_per_px, unsigned seed)
{
  return makeFrame(
      [slope_m_per_px](int u, int) {
        return u < kEdgeU + 2 ? kFaceDepthM : kFaceDepthM + slope_m_per_px * (u - kEdgeU - 2);
      },
      plainGrey, 0.004, seed);
}

TEST(EdgeEvidence, ASideFaceSeenAtAGrazingAngleOnAFarNoisyFaceIsARealEdge)
{
  // The side face of a row of bricks seen from the front at 2 m: most rows
  // alone stay under the step, all of them lie below the plane. Before,
  // such an edge read as the plane continuing, and a row of touching bricks
  // running off the image was not tiled at all (touching rows, frame 100).
  constexpr double kFaceRmsM = 0.006;
  for (unsigned seed = 1; seed <= 6; ++seed)
  {
    const EdgeKind kind = classify(farFaceFalling(0.0066, seed), kEdgeU, kFaceRmsM);
    EXPECT_TRUE(kind == EdgeKind::kCrease || kind == EdgeKind::kStepDown)
        << "seed " << seed << ": " << toString(kind);
  }
  // The same face going on 6 or 10 mm lower (a touching neighbour a little
  // lower, or a plane fitted a little off) shows no edge: half a step
  // (12 mm here) is the least the rows' median must fall.
  for (const double lower_m : {0.006, 0.010})
    for (unsigned seed = 1; seed <= 6; ++seed)
    {
      const RgbdFrame lower = makeFrame(
          [lower_m](int u, int) { return u < kEdgeU + 2 ? kFaceDepthM : kFaceDepthM + lower_m; }, plainGrey, 0.004,
          seed);
      EXPECT_FALSE(isRealEdge(classify(lower, kEdgeU, kFaceRmsM))) << lower_m << " m lower, seed " << seed;
    }
  // A band inside the edge raised 15 mm above the plane (a cover merged
  // into the face) with the plane going on beyond it: the outside lies below
  // the inside band, not below the face, and no edge is seen there.
  for (unsigned seed = 1; seed <= 6; ++seed)
  {
    const RgbdFrame raised = makeFrame(
        [](int u, int) { return u >= kEdgeU - 8 && u < kEdgeU ? kFaceDepthM - 0.015 : kFaceDepthM; }, plainGrey,
        0.004, seed);
    EXPECT_FALSE(isRealEdge(classify(raised, kEdgeU, kFaceRmsM))) << "raised inside, seed " << seed;
  }
}

/// The face covers u < edge_u; beyond the edge a surface 0.15 m nearer.
RgbdFrame nearerBeyond(double edge_u)
{
  return makeFrame([edge_u](int u, int) { return u < edge_u ? kFaceDepthM : kFaceDepthM - 0.15; }, plainGrey);
}

TEST(EdgeEvidence, NearerSurfaceTheCameraLooksOverIsAnOcclusion)
{
  // The edge is 60 px left of the principal point and the nearer surface
  // lies toward it: a wall 0.15 m tall standing on the edge would hide
  // 0.15 x 0.24 / 1.2 = 3 cm of the face, so the face may go on under it.
  constexpr double kEdgeLeftU = 100.0;
  EXPECT_EQ(classify(nearerBeyond(kEdgeLeftU), kEdgeLeftU), EdgeKind::kOcclusion);
  EXPECT_FALSE(isRealEdge(EdgeKind::kOcclusion));
}

TEST(EdgeEvidence, NearerSurfaceAlongAWallTheCameraSeesIsAStepUp)
{
  // Right of the principal point the camera sees a wall standing on the
  // edge; straight below it, the wall hides nothing either.
  for (const double edge_u : {220.0, kEdgeU})
    EXPECT_EQ(classify(nearerBeyond(edge_u), edge_u), EdgeKind::kStepUp) << edge_u;
  // Real only after RoiFilter has ruled out, by the wall's height, that
  // it rests on the face (BrickCatalogue::couldRiseTo).
  EXPECT_TRUE(isRealEdge(EdgeKind::kStepUp));
  EdgeEvidenceParams strict;
  strict.max_hidden_by_wall_m = 0.0;
  EXPECT_EQ(classifyEdge(nearerBeyond(220.0), facePlane(), Eigen::Vector2d(220.0, 30.0), Eigen::Vector2d(220.0, 210.0),
                         Eigen::Vector2d(1.0, 0.0), strict)
                .kind,
            EdgeKind::kStepUp);
}

/// Beyond the edge at `edge_u` a wall 0.15 m tall whose foot the stereo
/// matching window smooths over 16 px: its depth rises from 2 px out as a
/// smooth step; rows from `first_row_v` down (the face's plane goes on
/// above them).
RgbdFrame smoothedWallBeyond(double edge_u, int first_row_v = 0)
{
  return makeFrame(
      [edge_u, first_row_v](int u, int v) {
        if (v < first_row_v) return kFaceDepthM;
        const double x = std::clamp((u - edge_u - 2.0) / 16.0, 0.0, 1.0);
        return kFaceDepthM - 0.15 * x * x * (3.0 - 2.0 * x);
      },
      plainGrey);
}

TEST(EdgeEvidence, AWallWhoseFootTheStereoWindowSmoothsIsAStepUp)
{
  // With the step at 25 mm (a plane fitted with 6 mm rms, as on pallet
  // layers at 640x480), the band just beyond the edge (3-8 px) reads the
  // wall's foot: its median, 23 mm, is under the step. Its outer half
  // stands 35 mm up. Pallet frame 145 had three box_small tops beside a box_large
  // read so, as occlusions along the stretches where the wall read under the step.
  constexpr double kFaceRmsM = 0.00625;
  EXPECT_EQ(classify(smoothedWallBeyond(kEdgeU), kEdgeU, kFaceRmsM), EdgeKind::kStepUp);
  EXPECT_EQ(classify(smoothedWallBeyond(220.0), 220.0, kFaceRmsM), EdgeKind::kStepUp);
  // Beside half the edge only, the edge is no step up: the face's plane
  // going on beyond the other half leaves it no real edge.
  EXPECT_FALSE(isRealEdge(classify(smoothedWallBeyond(kEdgeU, 120), kEdgeU, kFaceRmsM)));
}

/// A step down along most of the edge at `edge_u`, a surface 0.15 m nearer
/// beyond its lower third.
RgbdFrame nearerBeyondLowerThird(double edge_u)
{
  return makeFrame(
      [edge_u](int u, int v) {
        if (u < edge_u) return kFaceDepthM;
        return v > 150 ? kFaceDepthM - 0.15 : kFaceDepthM + 0.2;
      },
      plainGrey);
}

TEST(EdgeEvidence, ANearerSurfaceTheCameraLooksOverAlongPartOfTheEdgeMakesItAnOcclusion)
{
  // Left of the principal point a wall standing on the edge would hide
  // 3 cm of the face: the face may go on under it.
  EXPECT_EQ(classify(nearerBeyondLowerThird(100.0), 100.0), EdgeKind::kOcclusion);
}

TEST(EdgeEvidence, ADropAlongPartOfTheEdgeAndAWallTheCameraSeesAlongTheRestEndTheFace)
{
  // The surface drops away beyond two thirds of the edge: the face ends at
  // that line. Beyond the last third a wall rises that the camera sees
  // (right of the principal point): a neighbour standing beside the face,
  // not a box on it, which would stand inside the line.
  const EdgeEvidence evidence = classifyEdge(nearerBeyondLowerThird(220.0), facePlane(), Eigen::Vector2d(220.0, 30.0),
                                             Eigen::Vector2d(220.0, 210.0), Eigen::Vector2d(1.0, 0.0));
  EXPECT_EQ(evidence.kind, EdgeKind::kDropBesideWall);
  EXPECT_TRUE(isRealEdge(EdgeKind::kDropBesideWall));
  EXPECT_NEAR(evidence.lowest_wall_m, 0.15, 0.01);
  EXPECT_NEAR(evidence.highest_wall_m, 0.15, 0.01);
}

TEST(EdgeEvidence, AnOccluderReachingOverTheFaceBesideADropIsAnOcclusion)
{
  // The same, but the nearer surface reaches 5 px over the face along the
  // lower third (a box lying across its corner, which the least-area quad
  // runs past): the band inside the edge is not on the face there.
  const RgbdFrame frame = makeFrame(
      [](int u, int v) {
        if (v > 150 && u >= 215) return kFaceDepthM - 0.15;
        return u < 220 ? kFaceDepthM : kFaceDepthM + 0.2;
      },
      plainGrey);
  EXPECT_EQ(classify(frame, 220.0), EdgeKind::kOcclusion);
}

TEST(EdgeEvidence, WallsOfTwoHeightsAllAlongTheEdgeAreAnOcclusionThatKeepsTheirHeights)
{
  // Two taller neighbours beside the face, 0.08 and 0.18 m above it (or
  // two boxes resting on it: RoiFilter tells by the face's size and
  // height above the support).
  const RgbdFrame frame = makeFrame(
      [](int u, int v) { return u < 220.0 ? kFaceDepthM : kFaceDepthM - (v < 120 ? 0.08 : 0.18); }, plainGrey);
  const EdgeEvidence evidence = classifyEdge(frame, facePlane(), Eigen::Vector2d(220.0, 30.0),
                                             Eigen::Vector2d(220.0, 210.0), Eigen::Vector2d(1.0, 0.0));
  EXPECT_EQ(evidence.kind, EdgeKind::kOcclusion);
  EXPECT_NEAR(evidence.lowest_wall_m, 0.08, 0.01);
  EXPECT_NEAR(evidence.highest_wall_m, 0.18, 0.01);
  // An occluder over part of the edge keeps none.
  const EdgeEvidence looked_over = classifyEdge(nearerBeyondLowerThird(100.0), facePlane(), Eigen::Vector2d(100.0, 30.0),
                                                Eigen::Vector2d(100.0, 210.0), Eigen::Vector2d(1.0, 0.0));
  EXPECT_TRUE(std::isnan(looked_over.lowest_wall_m));
}

TEST(EdgeEvidence, AWallWhoseHeightChangesAlongTheEdgeIsAnOcclusion)
{
  // A tilted surface beyond the edge, 0.10 m nearer at the top of the edge
  // and 0.20 m at its bottom: not the wall of a level neighbour.
  const RgbdFrame frame = makeFrame(
      [](int u, int v) { return u < 220.0 ? kFaceDepthM : kFaceDepthM - 0.10 - 0.10 * (v - 30) / 180.0; },
      plainGrey);
  EXPECT_EQ(classify(frame, 220.0), EdgeKind::kOcclusion);
}

// The edge's profiles leave out its ends (corners are rounded and mixed), so
// a brick lying across only the face's corner is judged there on its own.
TEST(EdgeEvidence, AnOccluderOverOnlyACornerIsSeenAtTheEdgeEnd)
{
  const auto depth = [](bool occluder) {
    return [occluder](int u, int v) {
      if (u < kEdgeU) return kFaceDepthM;
      return occluder && v < 40 ? kFaceDepthM - 0.15 : kFaceDepthM + 0.2;  // the edge starts at v 30
    };
  };
  const auto endsOf = [](const RgbdFrame& frame) {
    return occlusionAtEdgeEnds(frame, facePlane(), Eigen::Vector2d(kEdgeU, 30.0), Eigen::Vector2d(kEdgeU, 210.0),
                               Eigen::Vector2d(1.0, 0.0));
  };
  const RgbdFrame covered = makeFrame(depth(true), plainGrey);
  EXPECT_EQ(classify(covered), EdgeKind::kStepDown) << "the edge's own profiles do not reach the corner";
  EXPECT_EQ(endsOf(covered), EdgeKind::kOcclusion);
  const RgbdFrame clear = makeFrame(depth(false), plainGrey);
  EXPECT_EQ(endsOf(clear), EdgeKind::kUnknown);
}

TEST(EdgeEvidence, AWallOverAWholeEdgeEndIsAnOcclusionUnlessItIsTheEdgesOwnStepUp)
{
  // A nearer surface over the whole end next to corner 0 (v 30-44), the
  // camera straight above: as a wall it would hide nothing (a step up), but
  // on an edge that steps down elsewhere it is something lying across the
  // corner.
  const RgbdFrame frame = makeFrame(
      [](int u, int v) {
        if (u < kEdgeU) return kFaceDepthM;
        return v < 50 ? kFaceDepthM - 0.15 : kFaceDepthM + 0.2;
      },
      plainGrey);
  const auto endsOf = [&frame](double step_up_height_m) {
    return occlusionAtEdgeEnds(frame, facePlane(), Eigen::Vector2d(kEdgeU, 30.0), Eigen::Vector2d(kEdgeU, 210.0),
                               Eigen::Vector2d(1.0, 0.0), EdgeEvidenceParams(), step_up_height_m);
  };
  EXPECT_EQ(endsOf(std::numeric_limits<double>::quiet_NaN()), EdgeKind::kOcclusion);
  // On an edge that is itself a step up to a wall 0.15 m high, the same
  // wall reaching the corner is that wall; one of another height, seen by
  // the camera with the face clear inside the corner, is another neighbour
  // standing beside the corner (see the next test for one reaching over).
  EXPECT_EQ(endsOf(0.15), EdgeKind::kUnknown);
  EXPECT_EQ(endsOf(0.25), EdgeKind::kUnknown);
  // Beside walls from 0.10 to 0.20 m high, a 0.15 m wall at the end is one of them.
  EXPECT_EQ(occlusionAtEdgeEnds(frame, facePlane(), Eigen::Vector2d(kEdgeU, 30.0), Eigen::Vector2d(kEdgeU, 210.0),
                                Eigen::Vector2d(1.0, 0.0), EdgeEvidenceParams(), 0.10, 0.20),
            EdgeKind::kUnknown);
}

// Bench pallet-layer frame 142 (640x480): a flat box's edge beside a taller
// box's wall ended at a corner where that wall ends and a box of the
// flat's own height goes on: its end read half wall, half level, with
// nothing dropping, and was taken for something lying across the corner.
// Frame 147: the same corner at the end of an edge along a neighbour of the
// box's own height.
TEST(EdgeEvidence, AWallEndingBesideALevelNeighbourAtAnEdgesEndLeavesTheCornerClear)
{
  const auto depth = [](double edge_u, bool reaching_over) {
    return [edge_u, reaching_over](int u, int v) {
      if (u < edge_u) return reaching_over && v < 37 && u > edge_u - 6 ? kFaceDepthM - 0.05 : kFaceDepthM;
      return v < 37 ? kFaceDepthM - 0.15 : kFaceDepthM;  // the end next to corner 0 is v 30-44
    };
  };
  const auto endsOf = [](const RgbdFrame& frame, double edge_u, double wall_m) {
    return occlusionAtEdgeEnds(frame, facePlane(), Eigen::Vector2d(edge_u, 30.0), Eigen::Vector2d(edge_u, 210.0),
                               Eigen::Vector2d(1.0, 0.0), EdgeEvidenceParams(), wall_m);
  };
  constexpr double kNoWall = std::numeric_limits<double>::quiet_NaN();
  // The wall the camera sees ending beside a level neighbour hides
  // nothing of the face, beside an edge kept as walls or any other.
  const RgbdFrame corner = makeFrame(depth(kEdgeU, false), plainGrey);
  EXPECT_EQ(endsOf(corner, kEdgeU, 0.15), EdgeKind::kUnknown);
  EXPECT_EQ(endsOf(corner, kEdgeU, kNoWall), EdgeKind::kUnknown);
  // Something reaching over the face there is an occluder; so is a wall
  // the camera looks over (left of the principal point, the wall would
  // hide 3 cm of the face).
  EXPECT_EQ(endsOf(makeFrame(depth(kEdgeU, true), plainGrey), kEdgeU, 0.15), EdgeKind::kOcclusion);
  EXPECT_EQ(endsOf(makeFrame(depth(100.0, false), plainGrey), 100.0, kNoWall), EdgeKind::kOcclusion);
}

// Bench pallet-layer frame 141 (VGA): a row of flat boxes beside a wall of
// taller ones. Along each flat's edge the wall read 0.158-0.161 m high, at
// its ends 0.149 and 0.170 m (a seen wall reads as the height the profile
// meets it at): each end was "something else" lying across the corner, and
// the flats' size could not tell their type. What lies across a corner
// covers the face inside the edge too.
TEST(EdgeEvidence, AnotherWallAtAnEndOfAWalledEdgeReachingOverTheFaceIsAnOcclusion)
{
  // As above, but the nearer surface at the end also covers the face for
  // 8 px inside the edge: something lying across the corner.
  const RgbdFrame frame = makeFrame(
      [](int u, int v) {
        if (u < kEdgeU - 8) return kFaceDepthM;
        if (v < 50) return kFaceDepthM - 0.15;
        return u < kEdgeU ? kFaceDepthM : kFaceDepthM - 0.25;
      },
      plainGrey);
  const auto endsOf = [&frame](double wall_m) {
    return occlusionAtEdgeEnds(frame, facePlane(), Eigen::Vector2d(kEdgeU, 30.0), Eigen::Vector2d(kEdgeU, 210.0),
                               Eigen::Vector2d(1.0, 0.0), EdgeEvidenceParams(), wall_m);
  };
  EXPECT_EQ(endsOf(0.25), EdgeKind::kOcclusion);
  // Without a wall of the edge's own, any wall at an end still counts.
  EXPECT_EQ(endsOf(std::numeric_limits<double>::quiet_NaN()), EdgeKind::kOcclusion);
}

// A D4xx carries a face's depth a few pixels over a step down: the depth
// edge lies outside the face, whose colour ends inside it.
TEST(EdgeEvidence, AStepDownsColourEdgeInsideItsDepthEdgeIsMeasured)
{
  const auto depth = [](int u, int) { return u < kEdgeU ? kFaceDepthM : kFaceDepthM + 0.2; };
  const auto insetWhereColourEndsAt = [&](double colour_edge_u, double beyond_grey) {
    const RgbdFrame frame =
        makeFrame(depth, [=](int u, int) { return u < colour_edge_u ? 150.0 : beyond_grey; });
    return stepEdgeInsetPx(frame, facePlane(), Eigen::Vector2d(kEdgeU, 30.0), Eigen::Vector2d(kEdgeU, 210.0),
                           Eigen::Vector2d(1.0, 0.0));
  };
  EXPECT_NEAR(insetWhereColourEndsAt(kEdgeU - 4.0, 90.0), 4.0, 1.0);
  EXPECT_NEAR(insetWhereColourEndsAt(kEdgeU - 4.0, 210.0), 4.0, 1.0) << "a brighter surface beyond";
  EXPECT_NEAR(insetWhereColourEndsAt(kEdgeU, 90.0), 0.0, 1.0);
  // The same cardboard beyond: colour cannot tell.
  EXPECT_TRUE(std::isnan(insetWhereColourEndsAt(kEdgeU - 4.0, 150.0)));
}

/// Beyond the edge at kEdgeU a wall 0.15 m nearer, whose depth the sensor
/// carried 5 px over the face (its colour ends at kEdgeU + 5), then the
/// wall's foot: a line `line_darkening` grey levels darker, 3 px wide.
RgbdFrame wallFattenedOverFace(double line_darkening)
{
  return makeFrame([](int u, int) { return u < kEdgeU ? kFaceDepthM : kFaceDepthM - 0.15; },
                   [line_darkening](int u, int) {
                     return u >= kEdgeU + 5 && u < kEdgeU + 8 ? 150.0 - line_darkening : 150.0;
                   });
}

double footShift(const RgbdFrame& frame, double edge_u = kEdgeU)
{
  return wallFootShiftPx(frame, facePlane(), Eigen::Vector2d(edge_u, 30.0), Eigen::Vector2d(edge_u, 210.0),
                         Eigen::Vector2d(1.0, 0.0));
}

TEST(EdgeEvidence, TheFacesEdgeBesideAWallIsWhereItsColourEnds)
{
  // The depth edge is 5 px short; the face's last pixel in colour is
  // kEdgeU + 4, so its edge runs half a pixel beyond it.
  EXPECT_NEAR(footShift(wallFattenedOverFace(60.0)), 4.5, 0.3);
  // A colour edge at the depth edge: nothing to move.
  const RgbdFrame sharp = makeFrame([](int u, int) { return u < kEdgeU ? kFaceDepthM : kFaceDepthM - 0.15; },
                                    [](int u, int) { return u < kEdgeU ? 150.0 : 90.0; });
  EXPECT_NEAR(footShift(sharp), 0.0, 0.3);
  // No colour change within reach (8 px): unknown, the edge stays.
  EXPECT_TRUE(std::isnan(footShift(wallFattenedOverFace(0.0))));
  // A change fainter than the line contrast is none.
  EXPECT_TRUE(std::isnan(footShift(wallFattenedOverFace(3.0))));
}

TEST(EdgeEvidence, PlaneContinuingBeyondTheEdgeIsAMaskEdge)
{
  // The plane goes on with the same colour: the edge of a colour mask or a
  // cut from sizes alone, not where a brick ends.
  const RgbdFrame frame = makeFrame([](int, int) { return kFaceDepthM; }, plainGrey);
  EXPECT_EQ(classify(frame), EdgeKind::kMaskEdge);
  EXPECT_FALSE(isRealEdge(EdgeKind::kMaskEdge));
}

TEST(EdgeEvidence, AColourChangeOnOnePlaneIsNotASeam)
{
  // A label's border or the end of a colour mask: a step in colour, no line.
  const RgbdFrame frame = makeFrame([](int, int) { return kFaceDepthM; },
                                    [](int u, int) { return u < kEdgeU ? 150.0 : 90.0; });
  EXPECT_EQ(classify(frame), EdgeKind::kMaskEdge);
}

TEST(EdgeEvidence, FaintGrooveUnderNoiseIsASeam)
{
  // Touching boxes: depth smoothed across the seam leaves a groove 2 mm deep
  // and a few pixels wide under 1.5 mm of per-pixel noise; colour is plain.
  const RgbdFrame frame = makeFrame(
      [](int u, int) {
        const double d = std::abs(u - kEdgeU);
        return kFaceDepthM + (d < 3.0 ? 0.002 * (1.0 - d / 3.0) : 0.0);
      },
      plainGrey);
  EXPECT_EQ(classify(frame), EdgeKind::kSeam);
  EXPECT_TRUE(isRealEdge(EdgeKind::kSeam));
}

TEST(EdgeEvidence, DarkLineOnOnePlaneIsAColourLineRealOnlyOnAPlainPlate)
{
  // No groove: a seam between touching plates of one colour, or print on a
  // box; only a face found by its uniform colour may take it for a seam.
  const RgbdFrame frame = makeFrame([](int, int) { return kFaceDepthM; },
                                    [](int u, int) { return std::abs(u - kEdgeU) < 1.0 ? 110.0 : 150.0; });
  EXPECT_EQ(classify(frame), EdgeKind::kColourLine);
  EXPECT_TRUE(isRealEdge(EdgeKind::kColourLine, true));
  EXPECT_FALSE(isRealEdge(EdgeKind::kColourLine, false));
}

TEST(EdgeEvidence, GrooveWithADarkLineIsASeam)
{
  const RgbdFrame frame = makeFrame(
      [](int u, int) {
        const double d = std::abs(u - kEdgeU);
        return kFaceDepthM + (d < 3.0 ? 0.002 * (1.0 - d / 3.0) : 0.0);
      },
      [](int u, int) { return std::abs(u - kEdgeU) < 1.0 ? 110.0 : 150.0; });
  EXPECT_EQ(classify(frame), EdgeKind::kSeam);
}

TEST(EdgeEvidence, AGrooveOfNoiseOnlyIsNotASeam)
{
  // The same plane with 3 mm of noise and no groove, for several seeds: the
  // seam test must not fire on noise.
  for (unsigned seed = 1; seed <= 6; ++seed)
  {
    const RgbdFrame frame = makeFrame([](int, int) { return kFaceDepthM; }, plainGrey, 0.003, seed);
    EXPECT_EQ(classify(frame), EdgeKind::kMaskEdge) << "seed " << seed;
  }
}

TEST(EdgeEvidence, EdgeAlongTheImageBorderIsCutByTheBorder)
{
  const RgbdFrame frame = makeFrame([](int, int) { return kFaceDepthM; }, plainGrey);
  EXPECT_EQ(classify(frame, kWidth - 1.0), EdgeKind::kImageBorder);
  EXPECT_EQ(classify(frame, kWidth - 3.0), EdgeKind::kImageBorder);
}

TEST(EdgeEvidence, NoDepthBeyondTheEdgeSaysNothing)
{
  const RgbdFrame frame = makeFrame([](int u, int) { return u < kEdgeU ? kFaceDepthM : std::nan(""); }, plainGrey);
  EXPECT_EQ(classify(frame), EdgeKind::kNoDepth);
}

TEST(EdgeEvidence, SeamScoreFindsTheGrooveAcrossAFaceAndNotElsewhere)
{
  const RgbdFrame frame = makeFrame(
      [](int u, int) {
        const double d = std::abs(u - kEdgeU);
        return kFaceDepthM + (d < 3.0 ? 0.002 * (1.0 - d / 3.0) : 0.0);
      },
      plainGrey);
  const SeamScore on_seam =
      scoreSeam(frame, facePlane(), Eigen::Vector2d(kEdgeU, 30.0), Eigen::Vector2d(kEdgeU, 210.0));
  const SeamScore beside =
      scoreSeam(frame, facePlane(), Eigen::Vector2d(kEdgeU - 40.0, 30.0), Eigen::Vector2d(kEdgeU - 40.0, 210.0));
  EXPECT_TRUE(on_seam.seen);
  EXPECT_NEAR(on_seam.groove_m, 0.002, 0.001);
  EXPECT_FALSE(beside.seen);
  EXPECT_GT(on_seam.strength, beside.strength + 3.0);
}

TEST(EdgeEvidence, NamesAndParameterChecks)
{
  EXPECT_EQ(toString(EdgeKind::kOcclusion), "occlusion boundary");
  EXPECT_EQ(toString(EdgeKind::kImageBorder), "image border");
  EdgeEvidenceParams params;
  EXPECT_NO_THROW(params.validate());
  params.probe_px = 2;
  EXPECT_THROW(params.validate(), ConfigError);
  params = EdgeEvidenceParams();
  params.min_groove_m = 0.0;
  EXPECT_THROW(params.validate(), ConfigError);
}
}  // namespace
}  // namespace brick_pose
